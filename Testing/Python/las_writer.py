"""LAS files written from the specification (ASPRS LAS 1.4 R15, tables 3-4, 7, 8, 10, 11 and 12) for the main job's
tests: point formats 1 and 3 (LAS 1.2, or 1.4) and 6 and 7 (LAS 1.4), with the attributes a lidar file carries
(returns, scan angle, classification and its flags, GPS time, colours) and variable-length records (a coordinate
system). Independent of the project's reader: the tests read their results back through it and compare with what
was written here."""
import struct

import numpy as np


def projection_wkt_record(wkt):
    """The OGC coordinate-system WKT record (LASF_Projection 2112), NUL-terminated."""
    return ('LASF_Projection', 2112, wkt.encode() + b'\0')


def write_las(path, points, point_format=6, scale=1e-3, offset=None, returns=None, scan_angle=None,
              classification=None, withheld=None, colours=None, intensity=None, records=(), compressed=False,
              minor=None):
    """Writes `points` (n x 3) to `path` as LAS 1.4 (1.2 for formats 1 and 3 unless `minor` says) in `point_format`
    (1, 3, 6 or 7), positions rounded to `scale` from `offset` (default: a metre below the lowest corner). Per point,
    optional: `returns` (n x 2: return number, number of returns; default 1 of 1), `scan_angle` (degrees), the ASPRS
    `classification`, `withheld` flags, `colours` (n x 3, 0-255, scaled to 16 bits; formats 3 and 7), `intensity`.
    `records`:
    (user id, record id, bytes) variable-length records. `compressed` sets LAZ's flag in the format byte (the points
    stay plain: a reader must refuse the file, not decode it). Returns the positions as stored (the integers times
    the scale plus the offset)."""
    points = np.asarray(points, dtype=float)
    n = len(points)
    offset = points.min(axis=0) - 1.0 if offset is None else np.asarray(offset, dtype=float)
    q = np.round((points - offset) / scale).astype(np.int64)
    stored = q * scale + offset
    returns = np.ones((n, 2), dtype=int) if returns is None else np.asarray(returns, dtype=int)
    scan_angle = np.zeros(n) if scan_angle is None else np.asarray(scan_angle, dtype=float)
    classification = np.ones(n, dtype=int) if classification is None else np.asarray(classification, dtype=int)
    withheld = np.zeros(n, dtype=bool) if withheld is None else np.asarray(withheld, dtype=bool)
    colours = np.zeros((n, 3), dtype=int) if colours is None else np.asarray(colours, dtype=int)
    intensity = np.zeros(n, dtype=int) if intensity is None else np.asarray(intensity, dtype=int)
    extended = point_format >= 6
    minor = (4 if extended else 2) if minor is None else minor
    header_size = {2: 227, 3: 235, 4: 375}[minor]
    record_length = {1: 28, 3: 34, 6: 30, 7: 36}[point_format]
    vlrs = b''.join(struct.pack('<H16sHH32s', 0, user.encode(), rid, len(body), b'a record') + body
                    for user, rid, body in records)
    header = struct.pack('<4sHH16sBB32s32sHHHIIBHI5I3d3d6d', b'LASF', 0, 0, b'', 1, minor, b'GLS test', b'las_writer',
                         1, 2026, header_size, header_size + len(vlrs), len(records),
                         point_format | (0x80 if compressed else 0), record_length, 0 if extended else n,
                         0, 0, 0, 0, 0, scale, scale, scale, *offset,
                         stored[:, 0].max(), stored[:, 0].min(), stored[:, 1].max(), stored[:, 1].min(),
                         stored[:, 2].max(), stored[:, 2].min())
    if minor >= 3:
        header += struct.pack('<Q', 0)  # no waveform records
    if minor >= 4:
        header += struct.pack('<QIQ15Q', 0, 0, n, *([0] * 15))
    assert len(header) == header_size
    rows = []
    for i in range(n):
        number, count = int(returns[i, 0]), int(returns[i, 1])
        if extended:
            row = struct.pack('<3iHBBBBhHd', *q[i], int(intensity[i]), number | (count << 4), 4 if withheld[i] else 0,
                              int(classification[i]), 0, int(round(scan_angle[i] / 0.006)), 1, float(i))
        else:
            row = struct.pack('<3iHBBbBHd', *q[i], int(intensity[i]), number | (count << 3),
                              int(classification[i]) | (128 if withheld[i] else 0), int(round(scan_angle[i])), 0, 1,
                              float(i))
        if point_format in (3, 7):
            row += struct.pack('<3H', *(int(c) * 257 for c in colours[i]))
        assert len(row) == record_length
        rows.append(row)
    with open(path, 'wb') as f:
        f.write(header + vlrs + b''.join(rows))
    return stored


# The fields of LAS 1.4's point formats 6, 7 and 8 (table 16; 7 adds colours, 8 colours and near infrared).
_FORMAT_6 = [('X', '<i4'), ('Y', '<i4'), ('Z', '<i4'), ('intensity', '<u2'), ('returns', 'u1'), ('flags', 'u1'),
             ('classification', 'u1'), ('user_data', 'u1'), ('scan_angle', '<i2'), ('point_source', '<u2'),
             ('gps_time', '<f8')]
_POINT_FIELDS = {6: _FORMAT_6, 7: _FORMAT_6 + [('rgb', '<u2', 3)], 8: _FORMAT_6 + [('rgb', '<u2', 3), ('nir', '<u2')]}


def read_las(path):
    """Reads a LAS 1.4 file in point format 6, 7 or 8 from the specification, independently of the project's reader:
    returns a dict with the header's `scale`, `offset` and `count`, the variable-length `records` ({(user id, record
    id): bytes}), `points` (a numpy record array of the standard fields, X Y Z the integers), and `extra` ({name:
    values} of the float32 Extra Bytes fields its descriptors name)."""
    with open(path, 'rb') as f:
        data = f.read()
    assert data[:4] == b'LASF', path
    header_size, point_offset, record_count = struct.unpack_from('<HII', data, 94)
    point_format, record_length = data[104] & 0x3F, struct.unpack_from('<H', data, 105)[0]
    scale, offset = np.array(struct.unpack_from('<3d', data, 131)), np.array(struct.unpack_from('<3d', data, 155))
    count = struct.unpack_from('<Q', data, 247)[0]
    records, at = {}, header_size
    for _ in range(record_count):
        user, rid, length = struct.unpack_from('<2x16sHH', data, at)
        records[(user.rstrip(b'\0').decode(), rid)] = data[at + 54:at + 54 + length]
        at += 54 + length
    fields = _POINT_FIELDS[point_format]
    standard = np.dtype(fields).itemsize
    extra_fields, names = [], []
    descriptors = records.get(('LASF_Spec', 4), b'')
    for d in range(len(descriptors) // 192):
        data_type, name = descriptors[192 * d + 2], descriptors[192 * d + 4:192 * d + 36].rstrip(b'\0').decode()
        assert data_type == 9, 'only float32 fields expected here'
        extra_fields.append(('extra_%d' % d, '<f4'))
        names.append(name)
    padding = record_length - standard - 4 * len(names)
    assert padding >= 0, 'records shorter than their fields'
    dtype = np.dtype(fields + extra_fields + ([('padding', 'u1', padding)] if padding else []))
    points = np.frombuffer(data, dtype=dtype, count=count, offset=point_offset)
    extra = {name: points['extra_%d' % d] for d, name in enumerate(names)}
    return {'scale': scale, 'offset': offset, 'count': count, 'records': records, 'points': points,
            'extra': extra, 'format': point_format}
