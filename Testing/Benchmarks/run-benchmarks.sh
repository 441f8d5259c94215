#!/usr/bin/env bash
# Runs the performance benchmarks P1-P5 (P5 in a process of its own, for its peak memory), then the normals and the
# large-scan
# benchmark, with the peer columns
# when the peers are installed (CloudCompare in P1 adds 5 to 6 minutes here; docs/performance-peers.md).
#   Testing/Benchmarks/run-benchmarks.sh [build dir = build]
set -euo pipefail
bin="${1:-build}/bin/glsBenchmarks"
"$bin" --case all
"$bin" --case P5
# Normals under simulated scanner sampling, the noisy bunny, and the time on 1M points (docs/normals.md).
"${1:-build}/bin/glsNormalsBenchmark"
# Real scan sizes: the multi-resolution evaluation, L1-L3 and the accuracy table (about 40 minutes on 2 cores;
# docs/performance.md, "Large scans").
"${1:-build}/bin/glsLargeScanBenchmark" --case all
