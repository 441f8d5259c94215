"""The main job's result files: written into a staging folder inside the output directory, moved into place only
when every stage succeeded (commit), removed otherwise (discard): a failed run leaves no result behind (files of
an earlier run keep their place). Creating the staging folder first checks that the output directory is writable,
before any computation, and removes what a killed job left there (its process gone)."""
import ctypes
import os
import shutil
import signal
import sys
import tempfile

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import gls_watch


class OutputError(Exception):
    """The output directory cannot be created or written, or a file in it (one line for the user)."""


STAGING_PREFIX = '.gls-analyze-'


def remove_stale_staging(directory):
    """Removes the staging folders (<STAGING_PREFIX><pid>-...) that a job left behind in `directory` when it was
    killed (SIGKILL, a power cut): those whose process no longer runs. A running job's folder stays."""
    try:
        entries = os.listdir(directory)
    except OSError:
        return
    for entry in entries:
        if not entry.startswith(STAGING_PREFIX):
            continue
        owner = entry[len(STAGING_PREFIX):].split('-')[0]
        alive = False
        if owner.isdigit():
            try:
                os.kill(int(owner), 0)
                alive = True
            except ProcessLookupError:
                pass
            except PermissionError:  # another user's running job
                alive = True
        if not alive:
            shutil.rmtree(os.path.join(directory, entry), ignore_errors=True)


class Outputs:
    def __init__(self, directory, name):
        self.directory = directory
        self.name = name
        try:
            os.makedirs(directory, exist_ok=True)
            remove_stale_staging(directory)
            self.staging = tempfile.mkdtemp(prefix='%s%d-' % (STAGING_PREFIX, os.getpid()), dir=directory)
        except OSError as e:
            raise OutputError('cannot write to the output directory %s: %s' % (directory, e.strerror or e))
        self.staged = []
        self.writes = []  # BackgroundWrite of staged files, finished by commit, cancelled by discard

    def write_in_background(self, output_format, polydata):
        """Starts writing `polydata` to <name>-gls.<output_format> (FORMATS) while the job goes on; returns the
        BackgroundWrite (finish() it before reading the file)."""
        write = BackgroundWrite(self.path('-gls.' + output_format), polydata, FORMATS[output_format])
        self.writes.append(write)
        return write

    def path(self, suffix):
        """Where the stage writes <name><suffix> (in the staging folder)."""
        path = os.path.join(self.staging, self.name + suffix)
        self.staged.append(suffix)
        return path

    def final(self, suffix):
        """Where <name><suffix> lies once committed."""
        return os.path.join(self.directory, self.name + suffix)

    def commit(self):
        """Moves the staged files into the output directory; returns their final paths."""
        for write in self.writes:
            write.finish()
        moved = []
        for suffix in self.staged:
            source = os.path.join(self.staging, self.name + suffix)
            if os.path.exists(source):
                os.replace(source, self.final(suffix))
                moved.append(self.final(suffix))
        shutil.rmtree(self.staging, ignore_errors=True)
        return moved

    def discard(self):
        for write in self.writes:
            write.cancel()
        shutil.rmtree(self.staging, ignore_errors=True)


class BackgroundWrite:
    """A file writer (write_vtp, write_las, write_ply) in a child process, so that the pictures, the profiles and the
    denoising run while it writes (the .vtp's zlib at 10M points: about 9 s of one core). The child is forked: it sees the data as they are at the fork
    (copy-on-write: no second copy in memory, and nothing the job does next can change what is written). It dies
    with the job (Ctrl-C reaches it at once; it is killed if the job is). finish() waits for it and raises
    OutputError with the child's reason (sent through a pipe: the job's one error line says it) if it failed;
    cancel() kills it, so that the staging folder can be removed. Without os.fork (not POSIX) the file is written
    at once (OutputError then comes from the constructor)."""

    def __init__(self, path, polydata, write=None):
        write = write or write_vtp
        self.path = path
        self.pid = None
        self.reason = None  # the read end of the pipe the child writes why it failed to
        if not hasattr(os, 'fork'):
            write(path, polydata)
            return
        sys.stdout.flush()
        sys.stderr.flush()
        parent = os.getpid()
        reason, report = os.pipe()
        pid = os.fork()
        if pid == 0:
            os.close(reason)
            _write_and_exit(write, path, polydata, parent, report)
        os.close(report)
        self.pid, self.reason = pid, reason

    def finish(self):
        if self.pid is None:
            return
        _, status = os.waitpid(self.pid, 0)
        self.pid = None
        with os.fdopen(self.reason, 'rb') as pipe:
            why = pipe.read().decode(errors='replace').strip()
        self.reason = None
        if status != 0:
            raise OutputError(why or 'cannot write %s (the writing process ended with status %d)' % (self.path, status))

    def cancel(self):
        if self.pid is None:
            return
        try:
            os.kill(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        os.waitpid(self.pid, 0)
        os.close(self.reason)
        self.pid, self.reason = None, None


def _write_and_exit(write, path, polydata, parent, report):
    """The forked child of BackgroundWrite: write(path, polydata) and ends with status 0, or writes why not to the
    descriptor `report` and ends with 1, without running any of the job's exit handlers (os._exit: the X connection
    and the staging folder are the job's)."""
    status = 1
    try:
        signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C (the terminal signals the whole group) ends it now
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        try:  # Linux: killed when the job ends, however it ends
            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (AttributeError, OSError):
            pass
        # Only the forking thread lives on in the child, so the child writes on that one thread, whatever SMP
        # backend the job runs (VTK_SMP_BACKEND_IN_USE may choose STDThread, whose pool's threads are not copied).
        from vtkmodules.vtkCommonCore import vtkSMPTools
        vtkSMPTools.SetBackend('Sequential')
        if os.getppid() == parent:  # else the job ended before prctl took effect
            write(path, polydata)
            status = 0
    except BaseException as e:  # the child must reach os._exit whatever happens
        try:
            os.write(report, str(e).encode(errors='replace'))
        except OSError:
            pass
    finally:
        os._exit(status)


# The default output's GLS arrays (docs/main-job.md, "The default arrays"): float32 (most of them then rounded:
# SUMMARY_MANTISSA_BITS), the count as uint8; the per-scale arrays only with --per-scale.
SUMMARY_FLOAT32 = ('Normals', 'NormalQuality', 'GLSFeature', 'GLSStableScale', 'GLSStableTau', 'GLSStableKappa',
                   'GLSStablePhi', 'GLSMaxVariation', 'GLSMaxVariationScale', 'GLSDissimilarity',
                   'GLSStableDirectionScale', 'GLSAnisotropy', 'GLSStableShapeIndex', 'GLSStableDirection')
SUMMARY_UINT8 = ('GLSPertinentScaleCount',)
# Mantissa bits kept of those float32 arrays (of float32's 23), rounded to nearest: a relative error of at most 2^-13
# (1.2e-4) for the descriptors, a hundred times below the multi-resolution evaluation's own error (docs/performance.md,
# "Accuracy against exact": p99 of 0.02 for f, 0.01 for t kappa and phi; the steadiest principal direction's
# components too, under 0.01 degree), and 2^-17 for the normals' components (under 0.001 degree: later fits read them).
# The zeroed low bits compress: 39 bytes a point instead of 47 without the principal directions. --full-precision
# keeps them.
SUMMARY_MANTISSA_BITS = {'Normals': 16, 'NormalQuality': 12, 'GLSFeature': 12, 'GLSStableTau': 12,
                         'GLSStableKappa': 12, 'GLSStablePhi': 12, 'GLSMaxVariation': 12, 'GLSDissimilarity': 12,
                         'GLSAnisotropy': 12, 'GLSStableShapeIndex': 12, 'GLSStableDirection': 12}
# Arrays of the analysis left out of the default output (the normal estimation's neighbour count; the principal
# directions' turn rate, and their ridge/valley map, which GLSStableShapeIndex gives).
SUMMARY_DROPPED = ('NormalNeighbors', 'GLSDirectionTurnRate', 'GLSRidgeValley')
def rounded_float32(values, bits, chunk=1 << 20):
    """float32 copies of `values` with `bits` of their 23 mantissa bits kept, rounded to nearest (ties away from
    zero); NaN and infinities stay, and a finite value that would round past the largest float32 is cut instead.
    Rounded `chunk` values at a time, so that the temporaries stay small beside a 10^8-value array."""
    import numpy as np
    narrow = np.array(values, dtype=np.float32)
    if bits >= 23:
        return narrow
    drop = 23 - bits
    mask = np.uint32((0xFFFFFFFF << drop) & 0xFFFFFFFF)
    half = np.uint32(1 << (drop - 1))
    exponent = np.uint32(0x7F800000)
    flat = narrow.reshape(-1).view(np.uint32)
    for start in range(0, len(flat), chunk):
        raw = flat[start:start + chunk]
        finite = (raw & exponent) != exponent
        rounded = (raw + half) & mask
        overflow = (rounded & exponent) == exponent
        np.copyto(raw, rounded, where=finite & ~overflow)
        np.bitwise_and(raw, mask, out=raw, where=finite & overflow)
    return narrow


def compact(polydata, full_precision=False):
    """The default output: the points as the file gave them (never narrowed: a LAS file's positions are its integers
    times its scale plus its offset, in doubles, exactly), the cells, the input's own arrays as they are and the GLS
    arrays in SUMMARY_FLOAT32 / SUMMARY_UINT8 precision, the float32 ones rounded to SUMMARY_MANTISSA_BITS unless
    `full_precision`. Returns (polydata, the arrays narrowed)."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    out = vtkPolyData()
    narrowed = []
    out.SetPoints(polydata.GetPoints())
    for kind in ('Verts', 'Lines', 'Polys', 'Strips'):
        getattr(out, 'Set' + kind)(getattr(polydata, 'Get' + kind)())
    out.GetFieldData().ShallowCopy(polydata.GetFieldData())
    source, target = polydata.GetPointData(), out.GetPointData()
    for i in range(source.GetNumberOfArrays()):
        array = source.GetAbstractArray(i)
        name = array.GetName()
        if name in SUMMARY_DROPPED:
            continue
        kind = np.float32 if name in SUMMARY_FLOAT32 else np.uint8 if name in SUMMARY_UINT8 else None
        values = vtk_to_numpy(array) if kind is not None else None
        bits = SUMMARY_MANTISSA_BITS.get(name) if kind == np.float32 and not full_precision else None
        # (The filters may have written float32 already, OutputPrecision Single: rounded all the same.)
        if kind is None or (values.dtype == kind and bits is None) or \
                (kind == np.uint8 and values.max(initial=0) > 255):
            target.AddArray(array)
            continue
        narrow = numpy_to_vtk(np.ascontiguousarray(values, dtype=kind) if bits is None else
                              rounded_float32(values, bits), deep=True)
        narrow.SetName(name)
        target.AddArray(narrow)
        narrowed.append(name)
    if source.GetScalars() is not None:
        target.SetActiveScalars(source.GetScalars().GetName())
    if target.GetArray('Normals') is not None:
        target.SetActiveNormals('Normals')
    return out, narrowed


def reported_errors(algorithm, ignored=None):
    """A list that fills with the one-line text (gls_watch.one_line) of each error `algorithm` reports from now on,
    but those whose text holds `ignored`."""
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, message):
        if ignored is None or ignored not in (message or ''):
            errors.append(gls_watch.one_line(message or ''))
    algorithm.AddObserver('ErrorEvent', on_error)
    return errors


# The .vtp's zlib level and block size (write_vtp).
WRITE_ZLIB_LEVEL = 1
WRITE_BLOCK_BYTES = 1 << 20


def write_vtp(path, polydata):
    """VTK XML polydata, zlib-compressed at level 1 in blocks of 1 MiB (at 10M points 8.7 s and 39.3 bytes a
    point, where VTK's default level 5 and 32 KiB blocks take 18.2 s for 39.0: docs/performance.md), its data
    appended raw after the XML (inline binary would be base64: a third larger); OutputError with VTK's reason when
    the file cannot be written. Reading it back, ParaView 5.11 prints a harmless "Error reading InformationKey ...
    L2_NORM_RANGE" for the vector arrays: its writer stores that range cache and its reader does not know the key;
    the data are read correctly."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetCompressorTypeToZLib()
    writer.SetCompressionLevel(WRITE_ZLIB_LEVEL)
    writer.SetBlockSize(WRITE_BLOCK_BYTES)
    writer.SetHeaderTypeToUInt64()
    if polydata.GetNumberOfPoints() < 2 ** 31 - 1 and polydata.GetNumberOfCells() < 2 ** 31 - 1:
        writer.SetIdTypeToInt32()  # the cells' ids in 4 bytes
    errors = reported_errors(writer)  # VTK's writer says why (it cannot open the file, the disk is full)
    if writer.Write() != 1 or writer.GetErrorCode() != 0 or errors:  # Write() returns 1 on some failures
        code = writer.GetErrorCode()
        # Below VTK's own codes (vtkErrorCode), the writer reports the system's errno (28: no space left).
        why = os.strerror(code) if 0 < code < 20000 else errors[0] if errors else 'VTK error code %d' % code
        raise OutputError('cannot write %s: %s' % (path, why))


def _write_with(writer, path, polydata):
    """Runs a GLS writer (vtkGLSLasWriter, vtkGLSPlyWriter) on `polydata`; OutputError with its reason."""
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    errors = reported_errors(writer)
    if writer.Write() != 1 or errors:
        code = writer.GetErrorCode()
        raise OutputError(errors[0] if errors else 'cannot write %s: %s' % (
            path, os.strerror(code) if 0 < code < 20000 else 'VTK error code %d' % code))


def write_las(path, polydata):
    """LAS 1.4 (vtkGLSLasWriter): the points as the file gave them (a LAS input's integers, scale and offset; else a
    scale chosen for their extent; missing returns left out), its lidar attributes, every GLS array as float32 Extra
    Bytes fields, the coordinate system."""
    from glsvtk.vtkGLSFilters import vtkGLSLasWriter
    _write_with(vtkGLSLasWriter(), path, polydata)


def write_ply(path, polydata):
    """Binary PLY (vtkGLSPlyWriter): the points, nx ny nz, red green blue, every GLS array as scalar_<name> float
    properties (CloudCompare's scalar fields), the faces; missing returns left out."""
    from glsvtk.vtkGLSFilters import vtkGLSPlyWriter
    _write_with(vtkGLSPlyWriter(), path, polydata)


# --output-format: the writer of each format (the file is <name>-gls.<format>).
FORMATS = {'vtp': write_vtp, 'las': write_las, 'ply': write_ply}


# The most points of the stand-in cloud that the state is built on (save_state).
STATE_STAND_IN_POINTS = 20000


def stand_in(polydata, limit=STATE_STAND_IN_POINTS):
    """A small cloud with the arrays, the field data and the bounds of `polydata`: every k-th point (at most about
    `limit`) and the points at the extremes of each axis, in one poly-vertex cell."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    import gls_cloud
    count = polydata.GetNumberOfPoints()
    positions = vtk_to_numpy(polydata.GetPoints().GetData())
    with np.errstate(invalid='ignore'):
        extremes = np.concatenate([np.nanargmin(positions, axis=0), np.nanargmax(positions, axis=0)]) \
            if np.isfinite(positions).any() else np.zeros(0, dtype=np.int64)
    keep = np.unique(np.concatenate([np.arange(0, count, max(1, count // limit)), extremes]))
    out = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(positions[keep]), deep=True))
    out.SetPoints(points)
    out.SetVerts(gls_cloud.poly_vertex_cell(len(keep)))
    source, target = polydata.GetPointData(), out.GetPointData()
    for a in range(source.GetNumberOfArrays()):
        array = source.GetArray(a)
        if array is None:  # not a numeric array
            continue
        values = numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(array)[keep]), deep=True)
        values.SetName(array.GetName())
        target.AddArray(values)
    if source.GetScalars() is not None:
        target.SetActiveScalars(source.GetScalars().GetName())
    if target.GetArray('Normals') is not None:
        target.SetActiveNormals('Normals')
    for a in range(polydata.GetFieldData().GetNumberOfArrays()):
        out.GetFieldData().AddArray(polydata.GetFieldData().GetAbstractArray(a))
    return out


def stand_in_points(reader):
    """The positions the state's reader gives (its stand-in cloud)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from paraview import servermanager
    return vtk_to_numpy(servermanager.Fetch(reader).GetPoints().GetData())


def _finite_rows(points):
    import numpy as np
    return points[np.isfinite(points).all(axis=1)]


def check_written(vtp, polydata):
    """Reads the written file's XML header back (not its data: a 10M-point file would take seconds): the reader
    must parse it without an error and find the points and point arrays of `polydata`."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    errors = reported_errors(reader, ignored='InformationKey')  # write_vtp's files' harmless unknown key
    reader.SetFileName(vtp)
    reader.UpdateInformation()
    expected = sorted(polydata.GetPointData().GetArrayName(a) for a in range(polydata.GetPointData().GetNumberOfArrays()))
    found = sorted(reader.GetPointArrayName(a) for a in range(reader.GetNumberOfPointArrays()))
    parser = reader.GetXMLParser()
    root = parser.GetRootElement() if parser is not None else None
    poly = root.FindNestedElementWithName('PolyData') if root is not None else None
    piece = poly.FindNestedElementWithName('Piece') if poly is not None else None
    points = piece.GetAttribute('NumberOfPoints') if piece is not None else None
    if not errors and points != str(polydata.GetNumberOfPoints()):
        errors.append('%s points instead of %d' % (points, polydata.GetNumberOfPoints()))
    if not errors and found != expected:
        errors.append('point arrays %s instead of %s' % (', '.join(found), ', '.join(expected)))
    if errors:
        raise gls_watch.StageError('reading the written %s back: %s' % (os.path.basename(vtp), errors[0]))


def save_state(path, vtp, final_vtp, polydata):
    """A ParaView state that opens the .vtp (staged at `vtp`, committed to `final_vtp`) coloured by the features
    (no plugin needed to open it). The state is built on a stand-in of `polydata` (its arrays and bounds, at most
    about 20,000 points: ParaView reads and draws what a state shows) and then names the final file; the written
    file's header is checked first (check_written)."""
    from paraview import simple
    check_written(vtp, polydata)
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import gls_render
    stand_in_vtp = os.path.join(os.path.dirname(vtp), '.state-stand-in.vtp')
    shown = stand_in(polydata)
    write_vtp(stand_in_vtp, shown)
    simple.ResetSession()
    reader = simple.XMLPolyDataReader(registrationName=os.path.basename(final_vtp),
                                      FileName=[os.path.abspath(stand_in_vtp)])
    view = simple.GetActiveViewOrCreate('RenderView')
    display = simple.Show(reader, view)
    simple.ColorBy(display, ('POINTS', 'GLSFeature'))
    lut = simple.GetColorTransferFunction('GLSFeature')
    lut.ApplyPreset('Inferno (matplotlib)', True)
    lut.RescaleTransferFunction(0.0, 1.0)
    display.SetScalarBarVisibility(view, True)
    # The camera framing the data, set here (ParaView's default camera looks at the origin: a georeferenced result
    # would open far out of view; nothing is rendered, so no window is made): looking along the direction the points
    # spread least, from as far as the bounding sphere needs at the view angle.
    points = vtk_to_numpy(shown.GetPoints().GetData())
    gls_render.frame_camera(view, points[np.isfinite(points).all(axis=1)])
    simple.SaveState(path)
    os.remove(stand_in_vtp)
    with open(path) as f:
        state = f.read()
    with open(path, 'w') as f:
        f.write(state.replace(os.path.abspath(stand_in_vtp), os.path.abspath(final_vtp)))
