"""The ParaView XML and the C++ classes agree: every property's command exists on its class, its default is the
C++ default, and its range is the range the C++ checks (GetSettingMinimum/GetSettingMaximum); and every checked
setting, set outside its range or to NaN, is refused when the filter runs (an error naming it, an empty output).

    pvpython test_xml_matches_cxx.py <GrowingLeastSquares.xml>      (PYTHONPATH holds the glsvtk package)

Base proxies (base_proxygroup/base_proxyname) are resolved as ParaView does (paraview-plugin/tools/filters_doc.py:
the base's properties first, a property with override="1" replacing the inherited one). Lists (repeat_command) and array selections
(SetInputArrayToProcess) have no scalar default and are skipped.
"""
import math
import os
import sys
import unittest

import glsvtk
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkFiltersSources import vtkSphereSource

# The XML's proxies and their resolved properties, as docs/filters.md is written from them.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'paraview-plugin', 'tools'))
from filters_doc import load, properties  # noqa: E402

XML = sys.argv[1]
INT_MAX = 2147483647
DOUBLE_MAX = 1.0e299  # VTK_DOUBLE_MAX
ID_MAX = 9223372036854775807
VECTOR_PROPERTIES = ('IntVectorProperty', 'DoubleVectorProperty', 'IdTypeVectorProperty')


def numbers(text, kind):
    convert = float if kind == 'DoubleVectorProperty' else int
    return [convert(v) for v in text.split()]


class XmlMatchesCxx(unittest.TestCase):
    def setUp(self):
        self.proxies, _ = load(XML)
        self.filters = [k for k in self.proxies if k[0] in ('filters', 'sources')]
        self.assertGreaterEqual(len(self.filters), 10)

    def each_property(self):
        for key in self.filters:
            cls = self.proxies[key].get('class')
            obj = getattr(glsvtk, cls)()
            for prop in properties(self.proxies, key):
                yield key[1], obj, prop

    def test_every_command_exists(self):
        for proxy, obj, prop in self.each_property():
            for attribute in ('command', 'clean_command'):
                command = prop.get(attribute)
                if command:
                    self.assertTrue(hasattr(obj, command), '%s.%s: %s has no %s' % (
                        proxy, prop.get('name'), obj.GetClassName(), command))

    def test_defaults_equal_the_cxx_defaults(self):
        checked = 0
        for proxy, obj, prop in self.each_property():
            command = prop.get('command') or ''
            if (prop.tag not in VECTOR_PROPERTIES or not command.startswith('Set') or prop.get('repeat_command')
                    or prop.get('default_values') is None):
                continue
            getter = getattr(obj, 'Get' + command[3:])
            value = getter()
            expected = numbers(prop.get('default_values'), prop.tag)
            actual = list(value) if isinstance(value, (tuple, list)) else [value]
            self.assertEqual([float(v) for v in actual], [float(v) for v in expected],
                             '%s.%s: XML default %s, C++ %s' % (proxy, prop.get('name'), expected, actual))
            checked += 1
        self.assertGreater(checked, 60)

    def test_ranges_equal_the_cxx_checks(self):
        checked = 0
        for proxy, obj, prop in self.each_property():
            command = prop.get('command') or ''
            if prop.tag not in VECTOR_PROPERTIES or not command.startswith('Set') or not hasattr(
                    obj, 'GetSettingMinimum'):
                continue
            name = command[3:]
            low, high = obj.GetSettingMinimum(name), obj.GetSettingMaximum(name)
            if math.isnan(low):
                continue  # not range-checked here: the filter validates the value itself (an error names it)
            label = '%s.%s' % (proxy, prop.get('name'))
            enum = prop.find('EnumerationDomain')
            if enum is not None:
                values = sorted(int(e.get('value')) for e in enum.findall('Entry'))
                self.assertEqual((values[0], values[-1]), (low, high), label + ': enumeration vs check')
                self.assertEqual(values, list(range(values[0], values[-1] + 1)), label + ': gaps in the enumeration')
            elif prop.find('BooleanDomain') is not None:
                self.assertEqual((low, high), (0, 1), label)
            else:
                domain = prop.find('IntRangeDomain')
                if domain is None:
                    domain = prop.find('DoubleRangeDomain')
                self.assertIsNotNone(domain, label + ': checked in C++ but no range in the XML')
                xml_min = domain.get('min')
                xml_max = domain.get('max')
                self.assertIsNotNone(xml_min, label + ': no minimum in the XML')
                self.assertEqual(float(xml_min), float(low), label + ': minimum')
                if xml_max is None:
                    self.assertIn(float(high), (float(INT_MAX), DOUBLE_MAX, float(ID_MAX)),
                                  label + ': the XML has no maximum but C++ checks %s' % high)
                else:
                    self.assertEqual(float(xml_max), float(high), label + ': maximum')
            checked += 1
        self.assertGreater(checked, 30)

    def test_every_checked_setting_out_of_range_is_refused(self):
        """Below the minimum, above a finite maximum and NaN (a double setting): an error naming the setting and the
        value given, and an empty output; the value is kept as given (not clamped)."""
        sphere = vtkSphereSource()
        sphere.SetThetaResolution(24)
        sphere.SetPhiResolution(24)
        sphere.Update()
        refused = 0
        for proxy, obj, prop in self.each_property():
            command = prop.get('command') or ''
            if not command.startswith('Set') or not hasattr(obj, 'GetSettingMinimum'):
                continue
            name = command[3:]
            low, high = obj.GetSettingMinimum(name), obj.GetSettingMaximum(name)
            if math.isnan(low):
                continue
            is_double = prop.tag == 'DoubleVectorProperty'
            if is_double:
                bad = [low - 0.5, float('nan')] + ([high + 0.5] if high < INT_MAX else [])
            else:
                bad = [int(low) - 1] + ([int(high) + 1] if high < INT_MAX else [])
            for value in bad:
                fresh = getattr(glsvtk, obj.GetClassName())()
                getattr(fresh, command)(value)
                kept = getattr(fresh, 'Get' + name)()
                self.assertTrue(kept == value or (math.isnan(kept) and math.isnan(value)),
                                '%s.%s: set %s, kept %s (clamped)' % (proxy, name, value, kept))
                errors = []

                @calldata_type(VTK_STRING)
                def on_error(caller, event, message, errors=errors):
                    errors.append(message)
                fresh.AddObserver('ErrorEvent', on_error)
                fresh.SetInputData(sphere.GetOutput())
                fresh.Update()
                label = '%s.%s = %s' % (proxy, name, value)
                self.assertTrue(any(('Invalid %s' % name) in m for m in errors), label + ': %s' % errors)
                output = fresh.GetOutputDataObject(0)
                self.assertEqual(output.GetNumberOfPoints() if hasattr(output, 'GetNumberOfPoints') else 0, 0,
                                 label + ': the output is not empty')
                refused += 1
        self.assertGreater(refused, 60)


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]], verbosity=2)
