"""Open3D's normal estimation for glsBenchmarks P4, in a process of its own (Debian's python3-open3d 0.16 pulls
Debian's VTK 9.1: never import it in pvpython or next to ParaView's VTK).

    /usr/bin/python3 open3d_normals.py <points.f64> <normals.f64> <radius> <max_nn>

Reads n x 3 little-endian doubles, runs PointCloud.estimate_normals with KDTreeSearchParamHybrid(radius, max_nn)
(the max_nn nearest neighbours within radius; PCA of their covariance), writes the n x 3 unit normals (unoriented)
and prints 'open3d <version> compute <wall s> <cpu s> busy-threads <n> OMP_NUM_THREADS <value or unset>' (busy
threads: those that used at least 10% of a core during the call); reading and writing are outside the timed call.
"""
import os
import sys
import time

import numpy as np

try:
    import open3d
except ImportError as error:
    print('open3d missing: %s (Debian package python3-open3d, run by /usr/bin/python3)' % error)
    sys.exit(3)

points_path, normals_path, radius, max_nn = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
points = np.fromfile(points_path, dtype='<f8').reshape(-1, 3)
cloud = open3d.geometry.PointCloud()
cloud.points = open3d.utility.Vector3dVector(points)


def thread_cpu_seconds():
    """{thread id: user + system seconds} of this process's threads (Linux /proc)."""
    ticks = os.sysconf('SC_CLK_TCK')
    seconds = {}
    for tid in os.listdir('/proc/self/task'):
        with open('/proc/self/task/%s/stat' % tid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
        seconds[tid] = (int(fields[11]) + int(fields[12])) / ticks  # utime, stime: fields 14, 15 of stat
    return seconds


before = thread_cpu_seconds()
wall, cpu = time.perf_counter(), time.process_time()
cloud.estimate_normals(search_param=open3d.geometry.KDTreeSearchParamHybrid(radius=radius, max_nn=max_nn))
wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
busy = sum(1 for tid, s in thread_cpu_seconds().items() if s - before.get(tid, 0.0) >= 0.1 * wall)
np.asarray(cloud.normals, dtype='<f8').tofile(normals_path)
print('open3d %s compute %.6f %.6f busy-threads %d OMP_NUM_THREADS %s'
      % (open3d.__version__, wall, cpu, busy, os.environ.get('OMP_NUM_THREADS', 'unset')))
