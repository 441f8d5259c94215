#!/usr/bin/env bash
# Runs the performance benchmarks P1-P5 (P5 in a process of its own, for its peak memory), then the normals and the
# large-scan benchmarks, with the peer columns when the peers are installed (CloudCompare in P1 adds 5 to 6 minutes
# here; docs/performance-peers.md), then the GPU benchmark.
#   Testing/Benchmarks/run-benchmarks.sh [build dir = build]
set -euo pipefail
bin="${1:-build}/bin/glsBenchmarks"
"$bin" --case all
"$bin" --case P5
# Normals under simulated scanner sampling, the noisy bunny, and the time on 1M points (docs/normals.md).
"${1:-build}/bin/glsNormalsBenchmark"
# The same scans of the smooth models' limit surfaces (Loop-subdivided twice), at 1200 and 4000 rays per scan line:
# how the share within 5 degrees depends on the scan's resolution (docs/normals.md, "Resolution").
for rays in 1200 4000; do
  "${1:-build}/bin/glsNormalsBenchmark" --models stanford-bunny,spot,cheburashka --subdivide 2 --samples-along "$rays" \
    --invariance 0 --noisy-points 0 --timing-points 0
done
# The principal curvatures' accuracy table, with CGAL's jet fitting beside it (docs/performance.md, "Principal
# curvatures"; seconds).
"${1:-build}/bin/glsCurvatureBenchmark"
# Real scan sizes: the multi-resolution evaluation, L1-L3 and the accuracy table (about 40 minutes on 2 cores;
# docs/performance.md, "Large scans").
"${1:-build}/bin/glsLargeScanBenchmark" --case all
# The main job end to end at 10M points beside L1 and the normals (M1, M3; docs/performance.md, "The main job at
# scale"; about 10 minutes for the two models).
"$(dirname "$0")/run-main-job-benchmark.sh" "${1:-build}"
# The CUDA backend against the CPU engine (docs/performance.md, "Backends: CPU and CUDA"): without a usable device its
# rows say why and only the CPU is timed.
"${1:-build}/bin/glsCudaBenchmark" --points 1000000 --repeat 3
