"""Writes docs/filters.md, the reference of every GLS filter, reader and writer, from the plugin's server-manager XML (the
one place where the properties, their defaults, ranges and documentation are written).

    python3 filters_doc.py GrowingLeastSquares.xml docs/filters.md            # write
    python3 filters_doc.py GrowingLeastSquares.xml docs/filters.md --check    # exit 1 when the file is stale

Base proxies are resolved as ParaView resolves them (the base's properties first; override="1" replaces).
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET

HEADER = """# The filters: properties and outputs

Generated from `paraview-plugin/GrowingLeastSquares.xml` by `paraview-plugin/tools/filters_doc.py` (a test,
`docs.filters_reference`, fails when this page is stale: run the tool to regenerate it). Names are those of the
ParaView properties, which are also the VTK setters (`SetX`) and the pvpython keywords; constructors in pvpython
are the labels without spaces (`GLS Scale Space` -> `GLSScaleSpace(...)`). Lengths are in `ScaleUnits` where a
filter has them (by default fractions of the bounding-box diagonal). Advanced properties (under the gear icon in
the GUI) are marked *adv*. The maths behind each output is in [math.md](math.md).
"""


def clean(text):
    return re.sub(r'\s+', ' ', (text or '').strip())


def documentation(element):
    doc = element.find('Documentation')
    if doc is None:
        return '', ''
    return clean(doc.get('short_help')), clean(doc.text)


def load(path):
    root = ET.parse(path).getroot()
    proxies, order = {}, []
    for group in root.findall('ProxyGroup'):
        for proxy in group.findall('SourceProxy') + group.findall('WriterProxy'):
            key = (group.get('name'), proxy.get('name'))
            proxies[key] = proxy
            order.append(key)
    return proxies, order


def properties(proxies, key):
    proxy = proxies[key]
    inherited = []
    if proxy.get('base_proxyname'):
        inherited = properties(proxies, (proxy.get('base_proxygroup'), proxy.get('base_proxyname')))
    own = [p for p in proxy if p.tag.endswith('Property')]
    overridden = {p.get('name') for p in own if p.get('override') == '1'}
    return [p for p in inherited if p.get('name') not in overridden] + own


def values(prop):
    """The accepted values: an enumeration, a boolean, a range, or an array selection."""
    enum = prop.find('EnumerationDomain')
    if enum is not None:
        return ', '.join('%s = %s' % (e.get('value'), e.get('text')) for e in enum.findall('Entry'))
    if prop.find('BooleanDomain') is not None:
        return '0 or 1'
    for tag in ('IntRangeDomain', 'DoubleRangeDomain'):
        domain = prop.find(tag)
        if domain is not None:
            low, high = domain.get('min'), domain.get('max')
            return '>= %s' % low if high is None else '%s to %s' % (low, high)
    if prop.find('ArrayListDomain') is not None:
        return 'a point array'
    if prop.find('FileListDomain') is not None:
        return 'a file name'
    if prop.tag == 'InputProperty':
        types = [d.get('value') for d in prop.iter('DataType')]
        return ', '.join(types)
    return ''


def default(prop):
    if prop.tag == 'InputProperty':
        return ''
    if prop.get('repeat_command'):
        return '(empty list)' if prop.get('number_of_elements') == '0' else prop.get('default_values', '')
    value = prop.get('default_values')
    if value is None:
        return ''
    enum = prop.find('EnumerationDomain')
    if enum is not None:
        for e in enum.findall('Entry'):
            if e.get('value') == value:
                return '%s (%s)' % (value, e.get('text'))
    return value


def render(path):
    proxies, order = load(path)
    out = [HEADER]
    for key in order:
        if key[0] not in ('sources', 'filters', 'writers'):
            continue
        proxy = proxies[key]
        short, long_doc = documentation(proxy)
        out.append('## %s\n' % proxy.get('label'))
        if proxy.tag == 'WriterProxy':
            extension = proxy.find('Hints/WriterFactory').get('extensions')
            out.append('`%s` (File > Save Data as .%s; pvpython `SaveData(\'out.%s\', source)`, VTK class `%s`). %s\n'
                       % (proxy.get('name'), extension, extension, proxy.get('class'), short))
        else:
            out.append('`%s` (pvpython `%s`, VTK class `%s`). %s\n' % (
                proxy.get('name'), re.sub(r'[^A-Za-z0-9]', '', proxy.get('label')), proxy.get('class'), short))
        if long_doc:
            out.append(long_doc + '\n')
        out.append('| property | default | values | what it does |')
        out.append('|---|---|---|---|')
        for prop in properties(proxies, key):
            if prop.get('panel_visibility') == 'never' and prop.tag != 'InputProperty' and key[0] == 'filters':
                continue  # hidden: ignored by this filter
            _, text = documentation(prop)
            name = prop.get('name') + (' *adv*' if prop.get('panel_visibility') == 'advanced' else '')
            out.append('| %s | %s | %s | %s |' % (name, default(prop), values(prop), text.replace('|', '\\|')))
        out.append('')
    return '\n'.join(out)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('xml')
    parser.add_argument('markdown')
    parser.add_argument('--check', action='store_true')
    args = parser.parse_args()
    text = render(args.xml)
    if args.check:
        with open(args.markdown, encoding='utf-8') as f:
            if f.read() != text:
                print('%s is stale: run python3 paraview-plugin/tools/filters_doc.py %s %s' % (
                    args.markdown, args.xml, args.markdown))
                return 1
        print('%s matches %s' % (args.markdown, args.xml))
        return 0
    with open(args.markdown, 'w', encoding='utf-8') as f:
        f.write(text)
    return 0


if __name__ == '__main__':
    sys.exit(main())
