"""What the two Python examples share: their command line and their output (a summary line and the .vtp file).

    input [output.vtp = gls-example.vtp] [query point id = 0]
"""
import sys


def arguments(usage):
    """(input, output, query point id) from sys.argv; prints `usage` and exits with status 2 when malformed."""
    try:
        if not 2 <= len(sys.argv) <= 4:
            raise ValueError
        return (sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else 'gls-example.vtp',
                int(sys.argv[3]) if len(sys.argv) > 3 else 0)
    except ValueError:
        print(usage, file=sys.stderr)
        sys.exit(2)


def report_and_write(result, output, query):
    """Prints the ranges of the features and the dissimilarity of `result` (a vtkPolyData) and writes it to
    `output`; exits with status 1 when the pipeline failed (no such arrays) or the file cannot be written."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    f = result.GetPointData().GetArray('GLSFeature')
    delta = result.GetPointData().GetArray('GLSDissimilarity')
    if f is None or delta is None:
        sys.exit('error: the pipeline failed (see the messages above)')
    print('%d points; GLSFeature in [%g, %g]; GLSDissimilarity to point %d in [%g, %g]'
          % ((result.GetNumberOfPoints(),) + f.GetRange() + (query,) + delta.GetRange()))
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(output)
    writer.SetInputData(result)
    writer.SetDataModeToBinary()  # inline binary: ParaView 5.11 misreads some appended files with many components
    if writer.Write() != 1:
        sys.exit('error: cannot write %s' % output)
    print('wrote %s' % output)
