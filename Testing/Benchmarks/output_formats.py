"""The main job's output formats side by side (docs/performance.md, "Output formats"; issue 60's target: writing LAS
or PLY takes at most the time of writing the .vtp): the main job's result file is read once, then written as .vtp,
.las and .ply by the main job's own writers (gls_outputs.FORMATS), in turn, `repeats` times; each format's best time,
its bytes per point and its time over the .vtp's.

    PYTHONPATH=build/lib/python3/dist-packages pvpython Testing/Benchmarks/output_formats.py <name>-gls.vtp [repeats]
"""
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'paraview-plugin', 'python'))
import gls_outputs  # noqa: E402 (the main job's own modules)


def main():
    source, repeats = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 3
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(source)
    reader.Update()
    polydata = reader.GetOutput()
    n = polydata.GetNumberOfPoints()
    best, size = {}, {}
    with tempfile.TemporaryDirectory() as work:
        for _ in range(repeats):
            for name, write in gls_outputs.FORMATS.items():
                path = os.path.join(work, 'out.' + name)
                start = time.perf_counter()
                write(path, polydata)
                elapsed = time.perf_counter() - start
                best[name] = min(best.get(name, elapsed), elapsed)
                size[name] = os.path.getsize(path)
                os.remove(path)
    arrays = polydata.GetPointData().GetNumberOfArrays()
    print('output formats: %d points, %d point arrays, best of %d (seconds, bytes per point, time / vtp)'
          % (n, arrays, repeats))
    for name in gls_outputs.FORMATS:
        print('  %-4s %7.2f s %6.1f B/pt %5.2fx%s' % (name, best[name], size[name] / max(n, 1),
                                                     best[name] / best['vtp'],
                                                     '' if name == 'vtp' else ' (target <= 1)'))
    print('output formats benchmark complete')


if __name__ == '__main__':
    main()
