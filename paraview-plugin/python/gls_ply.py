"""A check that a PLY file holds what its header declares, run before ParaView reads it: ParaView 5.11's PLY reader
aborts (ASCII) or crashes (binary) on a truncated file instead of reporting an error. check(path) returns None, or
a one-line description of what is missing ("the header declares 50 vertex records; the file ends at record 25").
A file without a PLY header is left to the reader (which refuses it)."""
import struct

SIZES = {'char': 1, 'int8': 1, 'uchar': 1, 'uint8': 1, 'short': 2, 'int16': 2, 'ushort': 2, 'uint16': 2,
         'int': 4, 'int32': 4, 'uint': 4, 'uint32': 4, 'float': 4, 'float32': 4, 'double': 8, 'float64': 8}
CODES = {1: 'B', 2: 'H', 4: 'I'}


def parse_header(data):
    """(format, elements [(name, count, [(list count type or None, value type)])], body offset), or None without a PLY
    header; ValueError, saying which line, when an element line gives no count."""
    end = data.find(b'end_header')
    if not data.startswith(b'ply') or end < 0:
        return None
    newline = data.find(b'\n', end)
    body = len(data) if newline < 0 else newline + 1
    fmt, elements = None, []
    for line in data[:end].decode('ascii', 'replace').splitlines():
        words = line.split()
        if len(words) >= 2 and words[0] == 'format':
            fmt = words[1]
        elif len(words) >= 3 and words[0] == 'element':
            if not words[2].isdigit():
                raise ValueError('the header line %r gives no count' % line.strip())
            elements.append((words[1], int(words[2]), []))
        elif len(words) >= 3 and words[0] == 'property' and elements:
            listed = words[1] == 'list' and len(words) >= 4
            elements[-1][2].append((words[2], words[3]) if listed else (None, words[1]))
    return fmt, elements, body


def check_ascii(body, elements):
    lines = (line.split() for line in body.split(b'\n') if line.strip())
    for name, count, properties in elements:
        for record in range(count):
            words = next(lines, None)
            if words is None:
                return 'the header declares %d %s records; the file ends at record %d' % (count, name, record)
            need = 0
            for list_type, _ in properties:
                if list_type is None:
                    need += 1
                elif need < len(words):
                    need += 1 + int(float(words[need]))
                else:
                    need += 1
            if len(words) < need:
                return '%s record %d has %d values, its properties need %d' % (name, record, len(words), need)
    return None


def binary_size(body, offset, count, properties, order):
    """The bytes the element takes from `offset`, or None when the file ends first."""
    fixed = [SIZES.get(t, 0) for lt, t in properties if lt is None]
    lists = [(i, SIZES.get(lt, 0), SIZES.get(t, 0)) for i, (lt, t) in enumerate(properties) if lt is not None]
    if not lists:
        return count * sum(fixed)
    if len(lists) == 1 and lists[0][1] in CODES:  # the common case: faces (scalars, one list, scalars)
        index, count_size, item_size = lists[0]
        before = sum(SIZES.get(t, 0) for _, t in properties[:index])
        after = sum(SIZES.get(t, 0) for _, t in properties[index + 1:])
        code = ('<' if order == 'little' else '>') + CODES[count_size]
        position = offset
        for _ in range(count):
            if position + before + count_size > len(body):
                return None
            n = struct.unpack_from(code, body, position + before)[0]
            position += before + count_size + n * item_size + after
        return position - offset
    return 0  # several lists in one element: not checked


def check_binary(body, elements, order):
    offset = 0
    for name, count, properties in elements:
        size = binary_size(body, offset, count, properties, order)
        if size is None or offset + size > len(body):
            return 'the header declares %d %s records; the file ends before the last of them' % (count, name)
        offset += size
    return None


def check(path):
    with open(path, 'rb') as f:
        data = f.read()
    try:
        header = parse_header(data)
    except ValueError as e:
        return 'a malformed header: %s' % e
    if header is None:
        return None
    fmt, elements, start = header
    body = data[start:]
    try:
        if fmt == 'ascii':
            return check_ascii(body, elements)
        if fmt in ('binary_little_endian', 'binary_big_endian'):
            return check_binary(body, elements, 'little' if fmt == 'binary_little_endian' else 'big')
    except (ValueError, struct.error) as e:
        return 'unreadable values (%s)' % e
    return None
