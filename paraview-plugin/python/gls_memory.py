"""The main job's memory check, made before any stage runs: what the analysis of N points at S scales needs, against
what the machine has available (or --memory-budget), with the figure and the option that would fit.

The estimate is a fixed part (pvpython, ParaView and the plugin) and a part per point, fitted to the main job's
measured peak resident memory and rounded up (docs/main-job.md, "Memory, checked first"): the default path (normals,
the fused features and summaries, the compact output) and, with --per-scale, every scale's arrays on top."""
import math

# The default path's peak resident memory, whatever the number of scales: FIXED_BYTES plus DEFAULT_BYTES_PER_POINT a
# point. Measured on the bunny sampled by area (VmHWM of each stage), eighth session (2026-12-06): the normals and the
# fused pass both peak at about 201 bytes a point beside the 340 MiB of pvpython and ParaView at 10M and 30M points
# (2,255 and 6,101 MiB). At 10^8 points more is asked: the normals peaked at 20.4 GiB (with the coincident points'
# map and copy of the cloud, 2.9 GiB), and the fused pass's own check asks for its outputs and its engine's footprint
# (158 bytes a point at 10^8 points, 131 at 10^7: the pyramid holds 1.32 nodes a point against 1.04) with a tenth in
# reserve (FILTER_SHARE): about 23.6 GiB in all, 250 bytes a point; the normal estimation's own check asks for 199
# bytes a point with a tenth in reserve beside the points read (233 bytes a point in all; it frees its copy of the
# points once its grid is built: its peak at 10M is now 2,026 MiB). The estimate follows the larger (250 bytes a
# point): 3.2, 7.8 and 24.1 GiB at 10M, 30M and 100M points, so that a cloud a filter of the job would refuse is
# refused before any stage runs.
FIXED_BYTES = 850.0 * 1024.0 ** 2
DEFAULT_BYTES_PER_POINT = 250.0
# With --per-scale: bytes per point and scale on top (the scale space, nu, and their copy in the written file).
PER_SCALE_BYTES_PER_POINT_SCALE = 240.0
GIB = 1024.0 ** 3
MIB = 1024.0 ** 2
# The part of what is left of the budget that a filter is given: the rest covers its allocations besides the ones it
# counts (its outputs, its copy of the cloud and its engine).
FILTER_SHARE = 0.9


class BudgetError(Exception):
    """The analysis would not fit (one line: the figure and what to change)."""


def kib_line_bytes(path, key):
    """The value of the line `key: N kB` of a /proc file, in bytes; None where the file does not say."""
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(key + ':'):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return None


def available_bytes():
    """MemAvailable of /proc/meminfo (bytes): what the machine can give; None where the file does not say."""
    return kib_line_bytes('/proc/meminfo', 'MemAvailable')


def resident_bytes():
    """VmRSS of /proc/self/status (bytes): what this process holds now; None where the file does not say."""
    return kib_line_bytes('/proc/self/status', 'VmRSS')


def machine_budget_bytes():
    """What this job may reach without --memory-budget: the memory available now and what it holds already; None
    where /proc does not say."""
    available = available_bytes()
    return None if available is None else available + (resident_bytes() or 0.0)


def filter_budget_mib(budget):
    """The MemoryBudget (MiB) of a GLS filter created now: FILTER_SHARE of what the main job's budget (bytes) leaves
    beside what this process holds, so that the filter (the normals, the fused pass) refuses, or cuts its fit into
    spatial tiles, rather than exceed it;
    0 (the filters' own default, half of the physical memory) where the budget is not known."""
    if budget is None:
        return 0.0
    held = resident_bytes() or 0.0
    return max(FILTER_SHARE * (budget - held), MIB) / MIB


def needed_bytes(points, scales, per_scale):
    """The estimated peak (bytes) of the main job on `points` points at `scales` scales."""
    per_point = DEFAULT_BYTES_PER_POINT + (PER_SCALE_BYTES_PER_POINT_SCALE * scales if per_scale else 0.0)
    return FIXED_BYTES + points * per_point


def check(points, scales, per_scale, budget_gib=None, announced=False):
    """Raises BudgetError when the estimate exceeds the budget (GiB; default: the memory available now, plus what
    this process already holds: the estimate is the job's whole peak, and after reading a 10^8-point file the job
    holds a few GiB of it). Returns (needed bytes, budget bytes or None). `announced`: the count is the file's
    header's (checked before the file is read; the message says so)."""
    budget = budget_gib * GIB if budget_gib is not None else machine_budget_bytes()
    needed = needed_bytes(points, scales, per_scale)
    if budget is None or needed <= budget:
        return needed, budget
    where = '--memory-budget' if budget_gib is not None else 'available'
    counted = ' (as the file\'s header announces)' if announced else ''
    default = needed_bytes(points, scales, False)
    if per_scale and default <= budget:
        fitting = int(math.floor(((budget - FIXED_BYTES) / points - DEFAULT_BYTES_PER_POINT)
                                 / PER_SCALE_BYTES_PER_POINT_SCALE))
        advice = 'drop --per-scale (the per-point summaries need about %.1f GiB)' % (default / GIB)
        if fitting >= 2:
            advice += ', or keep it with --scales %d' % fitting
        raise BudgetError('storing every scale (--per-scale) of %d points%s at %d scales needs about %.1f GiB, '
                           'above the %.1f GiB %s: %s' % (points, counted, scales, needed / GIB, budget / GIB,
                                                           where, advice))
    raise BudgetError('the analysis of %d points%s needs about %.1f GiB, above the %.1f GiB %s: analyse a part of '
                       'the cloud, or a machine with more memory' % (points, counted, default / GIB, budget / GIB,
                                                                       where))
