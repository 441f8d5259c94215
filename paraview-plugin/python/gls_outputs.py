"""The main job's result files: written into a staging folder inside the output directory, moved into place only
when every stage succeeded (commit), removed otherwise (discard): a failed run leaves no result behind (files of
an earlier run keep their place). Creating the staging folder first checks that the output directory is writable,
before any computation."""
import os
import shutil
import tempfile

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import gls_watch


class OutputError(Exception):
    """The output directory cannot be created or written (one line for the user)."""


class Outputs:
    def __init__(self, directory, name):
        self.directory = directory
        self.name = name
        try:
            os.makedirs(directory, exist_ok=True)
            self.staging = tempfile.mkdtemp(prefix='.gls-analyze-', dir=directory)
        except OSError as e:
            raise OutputError('cannot write to the output directory %s: %s' % (directory, e.strerror or e))
        self.staged = []

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
        moved = []
        for suffix in self.staged:
            source = os.path.join(self.staging, self.name + suffix)
            if os.path.exists(source):
                os.replace(source, self.final(suffix))
                moved.append(self.final(suffix))
        shutil.rmtree(self.staging, ignore_errors=True)
        return moved

    def discard(self):
        shutil.rmtree(self.staging, ignore_errors=True)


def write_vtp(path, polydata):
    """Inline binary VTK XML (ParaView 5.11's reader fails on some appended files). Reading it back, ParaView 5.11
    prints a harmless "Error reading InformationKey ... L2_NORM_RANGE" for the vector arrays: its writer stores
    that range cache and its reader does not know the key; the data are read correctly."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    writer.SetDataModeToBinary()
    writer.SetCompressorTypeToZLib()
    writer.SetHeaderTypeToUInt64()
    if writer.Write() != 1:
        raise OSError('cannot write %s' % path)


def save_state(path, vtp, final_vtp):
    """A ParaView state that opens the .vtp (staged at `vtp`, committed to `final_vtp`) coloured by the features
    (no plugin needed to open it)."""
    from paraview import simple
    simple.ResetSession()
    reader = simple.XMLPolyDataReader(registrationName=os.path.basename(final_vtp), FileName=[os.path.abspath(vtp)])
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, message):  # the harmless unknown-key message of write_vtp's files is dropped
        if 'InformationKey' not in message:
            errors.append(gls_watch.one_line(message))
    algorithm = reader.GetClientSideObject()  # a vtkFileSeriesReader around the vtkXMLPolyDataReader
    for target in (algorithm, getattr(algorithm, 'GetReader', lambda: None)()):
        if target is not None:
            target.AddObserver('ErrorEvent', on_error)
    view = simple.GetActiveViewOrCreate('RenderView')
    display = simple.Show(reader, view)
    simple.ColorBy(display, ('POINTS', 'GLSFeature'))
    lut = simple.GetColorTransferFunction('GLSFeature')
    lut.ApplyPreset('Inferno (matplotlib)', True)
    lut.RescaleTransferFunction(0.0, 1.0)
    display.SetScalarBarVisibility(view, True)
    view.ResetCamera()
    if errors:
        raise gls_watch.StageError('reading the written %s back: %s' % (os.path.basename(final_vtp), errors[0]))
    simple.SaveState(path)
    with open(path) as f:
        state = f.read()
    with open(path, 'w') as f:
        f.write(state.replace(os.path.abspath(vtp), os.path.abspath(final_vtp)))
