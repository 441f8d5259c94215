#!/usr/bin/env bash
# Runs the performance benchmarks P1-P5 (P5 in a process of its own, for its peak memory), then the normals
# benchmark, with the peer columns
# when the peers are installed (CloudCompare in P1 adds 5 to 6 minutes here; docs/performance-peers.md).
#   Testing/Benchmarks/run-benchmarks.sh [build dir = build]
set -euo pipefail
bin="${1:-build}/bin/glsBenchmarks"
"$bin" --case all
"$bin" --case P5
# Normals under simulated scanner sampling, the noisy bunny, and the time on 1M points (docs/normals.md).
"${1:-build}/bin/glsNormalsBenchmark"
