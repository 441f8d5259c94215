"""The main job's memory check, made before any stage runs: what the analysis of N points at S scales needs, against
what the machine has available (or --memory-budget), with the figure and the option that would fit.

The estimate is a fixed part (pvpython, ParaView and the plugin) and a part per point, fitted to the main job's
measured peak resident memory and rounded up (docs/main-job.md, "Memory, checked first"): the default path (normals,
the fused features and summaries, the compact output) and, with --per-scale, every scale's arrays on top."""
import math

# The default path's peak resident memory, whatever the number of scales: FIXED_BYTES plus default_bytes_per_point(N)
# a point, the larger of its two fits' asks, each within FILTER_SHARE of what the job leaves, beside what the job holds
# then. The normal estimation asks for 141 bytes a point (gls::normalEstimationBytes) beside the float32 positions: 12 +
# 141 / 0.95 = 161 (NORMALS_BYTES_PER_POINT). The fused pass (ScaleFilterBase) holds its engine while it is built, then
# the engine beside its outputs (32 bytes a point), which it makes once the engine is built: it asks for the larger.
# Its engine at its least, with compact normals (the pyramid keeps float32 normals as given; the filter turns them on
# when its budget asks for it): 109 bytes a point while built and 87 running at 10^8 points of the bunny sampled by
# area, 86.5 and 68.9 at 10^7 (the pyramid holds 1.32 and 1.04 nodes a point; ScaleSpaceEngine::footprint), with the
# filter's copy of the cloud (48 bytes a point) until the sorted one exists: 93 and 109 while built. Beside it the job
# holds the float32 positions, normals, normal quality and neighbour counts (32 bytes a point; the coincident points'
# map is kept as its later copies only): 32 + 100.9 / 0.95 = 139 bytes a point at 10^7 points (FUSED_BYTES_PER_POINT),
# 32 + 119.1 / 0.95 = 158 at 10^8 (DENSITY_BYTES_PER_POINT more for each tenfold beyond 10^7). The fused pass's fit
# cannot be cut into smaller tiles at the job's default scales (to 8% of the diagonal: each tile's band of neighbours
# holds most of the cloud), so the estimate is its untiled ask: a cloud a filter of the job would refuse is refused
# before any stage runs. Measured: docs/main-job.md, "Memory, checked first".
# With the principal directions (the fused pass's DirectionSummary; not with --no-directions) the pass holds more: its
# engine keeps the curvatures' cell sums (ShapeOperatorCells.h) and the directions' float32 outputs (32 bytes a point)
# sit beside the summaries. Measured: a 2.50 GiB peak at 10^7 points of the bunny (the job without them: 1.84 GiB),
# 850 MiB + 180 bytes a point, rounded up to DIRECTIONS_BYTES_PER_POINT; its growth with density (a denser pyramid,
# more summed cells a point) was not measured at 10^8 points: DIRECTIONS_DENSITY_BYTES_PER_POINT scales the fused
# pass's by the ratio of the two (an extrapolation; docs/main-job.md, "Memory, checked first").
FIXED_BYTES = 850.0 * 1024.0 ** 2
NORMALS_BYTES_PER_POINT = 161.0
FUSED_BYTES_PER_POINT = 139.0
DENSITY_BYTES_PER_POINT = 19.0
DIRECTIONS_BYTES_PER_POINT = 190.0
DIRECTIONS_DENSITY_BYTES_PER_POINT = 26.0
# With --per-scale: bytes per point and scale on top (the scale space, nu, and their copy in the written file).
PER_SCALE_BYTES_PER_POINT_SCALE = 240.0
GIB = 1024.0 ** 3
MIB = 1024.0 ** 2
# The part of what is left of the budget that a filter is given: the rest covers its allocations besides the ones it
# counts (its outputs, its copy of the cloud, its engine or its graph), which are small: the counts are bounds (at
# 10^8 points the fused pass peaked 1.9 GB below its count, the normals 0.8 GB below theirs).
FILTER_SHARE = 0.95


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


def default_bytes_per_point(points, directions=True):
    """The default path's bytes a point for a cloud of `points` points: the normals' NORMALS_BYTES_PER_POINT, the
    fused pass's FUSED_BYTES_PER_POINT up to 10^7 points and DENSITY_BYTES_PER_POINT more for each tenfold beyond (a
    denser cloud's pyramid holds more nodes a point), or with `directions` the principal directions' pass's
    (DIRECTIONS_BYTES_PER_POINT, DIRECTIONS_DENSITY_BYTES_PER_POINT), whichever is largest."""
    tenfolds = max(0.0, math.log10(max(points, 1) / 1e7))
    fused = FUSED_BYTES_PER_POINT + DENSITY_BYTES_PER_POINT * tenfolds
    if directions:
        fused = max(fused, DIRECTIONS_BYTES_PER_POINT + DIRECTIONS_DENSITY_BYTES_PER_POINT * tenfolds)
    return max(NORMALS_BYTES_PER_POINT, fused)


def needed_bytes(points, scales, per_scale, directions=True):
    """The estimated peak (bytes) of the main job on `points` points at `scales` scales (with the principal
    directions unless `directions` is False: --no-directions)."""
    per_point = default_bytes_per_point(points, directions) + \
        (PER_SCALE_BYTES_PER_POINT_SCALE * scales if per_scale else 0.0)
    return FIXED_BYTES + points * per_point


def check(points, scales, per_scale, budget_gib=None, announced=False, directions=True):
    """Raises BudgetError when the estimate exceeds the budget (GiB; default: the memory available now, plus what
    this process already holds: the estimate is the job's whole peak, and after reading a 10^8-point file the job
    holds a few GiB of it). Returns (needed bytes, budget bytes or None). `announced`: the count is the file's
    header's (checked before the file is read; the message says so)."""
    budget = budget_gib * GIB if budget_gib is not None else machine_budget_bytes()
    needed = needed_bytes(points, scales, per_scale, directions)
    if budget is None or needed <= budget:
        return needed, budget
    where = '--memory-budget' if budget_gib is not None else 'available'
    counted = ' (as the file\'s header announces)' if announced else ''
    default = needed_bytes(points, scales, False, directions)
    if per_scale and default <= budget:
        fitting = int(math.floor(((budget - FIXED_BYTES) / points - default_bytes_per_point(points, directions))
                                 / PER_SCALE_BYTES_PER_POINT_SCALE))
        advice = 'drop --per-scale (the per-point summaries need about %.1f GiB)' % (default / GIB)
        if fitting >= 2:
            advice += ', or keep it with --scales %d' % fitting
        raise BudgetError('storing every scale (--per-scale) of %d points%s at %d scales needs about %.1f GiB, '
                           'above the %.1f GiB %s: %s' % (points, counted, scales, needed / GIB, budget / GIB,
                                                           where, advice))
    without = needed_bytes(points, scales, per_scale, False)
    if directions and without <= budget:
        raise BudgetError('the analysis of %d points%s needs about %.1f GiB with the principal directions, above the '
                           '%.1f GiB %s: add --no-directions (without them it needs about %.1f GiB)'
                           % (points, counted, needed / GIB, budget / GIB, where, without / GIB))
    raise BudgetError('the analysis of %d points%s needs about %.1f GiB, above the %.1f GiB %s: analyse a part of '
                       'the cloud, or a machine with more memory' % (points, counted, default / GIB, budget / GIB,
                                                                       where))
