"""Point-cloud input for the GLS main job: PLY, OBJ, VTP through ParaView's readers, XYZ/PTS/CSV/TXT through the
plugin's GLS Point Cloud Reader (x y z [nx ny nz]; see vtkGLSPointCloudReader)."""
import os

SUPPORTED = ('.ply', '.obj', '.vtp', '.xyz', '.csv', '.txt', '.pts')


class InputError(Exception):
    """A missing, unreadable or malformed input file, with a message for the user."""


def open_cloud(path, make_proxy):
    """A ParaView source proxy producing the file's points (and normals if any); raises InputError.
    make_proxy(name, **properties) creates a plugin proxy (LoadPlugin put the constructors in the caller's module)."""
    from paraview import simple
    if not os.path.isfile(path):
        raise InputError('%s: no such file' % path)
    if not os.access(path, os.R_OK):
        raise InputError('%s: not readable (permissions)' % path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in SUPPORTED:
        raise InputError('%s: unsupported type %r (use %s)' % (path, ext, ', '.join(SUPPORTED)))
    if ext in ('.xyz', '.csv', '.txt', '.pts'):
        reader = make_proxy('GLSPointCloudReader', registrationName=os.path.basename(path), FileName=path)
        reader.UpdatePipeline()
        if reader.GetDataInformation().GetNumberOfPoints() == 0:
            raise InputError('%s: no points could be read (the reader says why above)' % path)
        return reader
    reader = simple.OpenDataFile(path)
    if reader is None:
        raise InputError('%s: ParaView has no reader for it' % path)
    reader.UpdatePipeline()
    info = reader.GetDataInformation()
    if info.GetNumberOfPoints() == 0:
        raise InputError('%s: unreadable or empty (no points)' % path)
    return reader
