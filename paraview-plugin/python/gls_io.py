"""Point-cloud input for the GLS main job: PLY, OBJ, STL, VTP through ParaView's readers, XYZ/PTS/CSV/TXT through
the plugin's GLS Point Cloud Reader (the column layouts are in docs/main-job.md and gls/PointTextParser.h), LAS (and
LAZ, refused with how to decompress it) through its GLS LAS Reader."""
import os

import gls_ply

READERS = {'.ply': 'ParaView (PLY)', '.obj': 'ParaView (OBJ)', '.stl': 'ParaView (STL)',
           '.vtp': 'ParaView (VTK XML polydata)'}
# The plugin's readers: the proxy of each extension, and its information property that says how the file was read.
POINT_CLOUD_READER = ('GLSPointCloudReader', 'columns ', 'ColumnLayout')
LAS_READER = ('GLSLASReader', '', 'Description')
PLUGIN_READERS = dict([(ext, POINT_CLOUD_READER) for ext in ('.xyz', '.pts', '.csv', '.txt', '.ptx', '.pcd')] +
                      [(ext, LAS_READER) for ext in ('.las', '.laz')])
SUPPORTED = tuple(READERS) + tuple(PLUGIN_READERS)
# Scanners' formats no Debian 12 package reads beside ParaView: why, and the converters that help.
CONVERT_FIRST = {
    '.e57': ('an E57 scan needs libE57Format, which Debian 12 does not package',
             'CloudCompare: File > Save as, LAS or PLY; or pdal translate in.e57 out.las'),
}


class InputError(Exception):
    """A missing, unreadable, empty or malformed input file, with a one-line message for the user."""


def check_file(path):
    """Raises InputError unless `path` is a readable file of a supported type (before ParaView starts)."""
    if os.path.isdir(path):
        raise InputError('%s: a directory, not a file (gls-analyze reads one point cloud or mesh file)' % path)
    if not os.path.isfile(path):
        raise InputError('%s: no such file' % path)
    if not os.access(path, os.R_OK):
        raise InputError('%s: not readable (permissions)' % path)
    ext = os.path.splitext(path)[1].lower()
    if ext in CONVERT_FIRST:
        raise InputError('%s: %s; convert it first (%s)' % (path, CONVERT_FIRST[ext][0], CONVERT_FIRST[ext][1]))
    if ext not in SUPPORTED:
        raise InputError('%s: unsupported type %r (use %s)' % (path, ext, ', '.join(SUPPORTED)))
    if os.path.getsize(path) == 0:
        raise InputError('%s: the file is empty' % path)


def announced_point_count(path):
    """The number of points a file's header announces, read from its header alone before anything else: PLY (its
    vertex element, gls_ply), LAS and LAZ, PCD (the plugin's readers' own header readers); None for the formats
    without one (text, PTX, OBJ, STL, VTP) or a header that cannot be read (the reader then reports what is wrong)."""
    ext = os.path.splitext(path)[1].lower()
    if ext == '.ply':
        try:
            with open(path, 'rb') as f:
                header = gls_ply.parse_header(f.read(65536))
        except (OSError, ValueError):
            return None  # a malformed header: the PLY check before the reader says what is wrong
        counts = [count for name, count, _ in header[1] if name == 'vertex'] if header else []
        return counts[0] if counts else None
    if ext in ('.las', '.laz', '.pcd'):
        from glsvtk.vtkGLSFilters import vtkGLSLasReader, vtkGLSPointCloudReader
        reader = vtkGLSPointCloudReader() if ext == '.pcd' else vtkGLSLasReader()
        reader.SetFileName(path)
        count = reader.ReadAnnouncedPointCount()
        return count if count >= 0 else None
    return None


def output_of(proxy, port=0):
    """The data a proxy's algorithm produced, without a copy of its arrays (the main job runs ParaView's builtin
    session, where the algorithm is in this process; servermanager.Fetch would deep-copy a 10M-point cloud)."""
    data = proxy.GetClientSideObject().GetOutputDataObject(port)
    shallow = data.NewInstance()
    shallow.ShallowCopy(data)
    return shallow


def release_output(proxy, port=0):
    """Empties what a proxy produced: its algorithm's output and the shallow copy of it that ParaView's post filter
    (the proxy's output port) holds, so that arrays no one else refers to are freed. The proxy must not be updated
    again."""
    from paraview import servermanager
    si = servermanager.ActiveConnection.Session.GetSIObject(proxy.GetGlobalID())
    si.GetOutputPort(port).GetProducer().GetOutputDataObject(0).Initialize()
    proxy.GetClientSideObject().GetOutputDataObject(port).Initialize()


def open_cloud(path, make_proxy, watch):
    """(source proxy, polydata, description of how it was read) for the file; raises InputError. make_proxy(name,
    **properties) creates a plugin proxy; watch (gls_watch.Watch) turns the reader's errors into the message."""
    from paraview import simple
    import gls_watch
    check_file(path)
    ext = os.path.splitext(path)[1].lower()
    if ext in PLUGIN_READERS:
        reader = make_proxy(PLUGIN_READERS[ext][0], registrationName=os.path.basename(path), FileName=path)
    else:
        damage = gls_ply.check(path) if ext == '.ply' else None
        if damage:  # ParaView's PLY reader would crash on it
            raise InputError('%s: a damaged or truncated PLY file: %s' % (path, damage))
        try:
            reader = simple.OpenDataFile(path)
        except RuntimeError:
            reader = None
        if reader is None:
            raise InputError('%s: no ParaView reader accepts it (not a valid %s file?)' % (path, ext[1:].upper()))
    watch.watch(reader, 'reader', progress=False)
    try:
        watch.update(reader)
    except gls_watch.StageError as e:
        raise InputError(str(e))
    data = output_of(reader)
    if not data.IsA('vtkPolyData'):
        raise InputError('%s: the reader gives a %s, not a point cloud or surface' % (path, data.GetClassName()))
    if data.GetNumberOfPoints() == 0:
        raise InputError('%s: no points (an empty %s file?)' % (path, ext[1:].upper()))
    if ext in PLUGIN_READERS:
        _, prefix, information = PLUGIN_READERS[ext]
        reader.UpdatePropertyInformation()
        description = prefix + reader.GetProperty(information).GetElement(0)
    else:
        description = 'read by %s' % READERS[ext]
    return reader, data, description
