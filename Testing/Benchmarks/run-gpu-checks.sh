#!/usr/bin/env bash
# The checks that need a CUDA device, in one go (docs/performance.md, "Backends: CPU and CUDA"): the tests labelled
# `cuda`, the whole core suite, the GPU benchmark on the bundled bunny and rocker arm, and compute-sanitizer's
# memcheck on one device test. Needs only a core build with CUDA (no VTK):
#
#   cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DGLS_BUILD_VTK=OFF -DGLS_ENABLE_CUDA=ON
#   cmake --build build-gpu -j
#   Testing/Benchmarks/run-gpu-checks.sh [build-gpu] [log folder (.)]
#
# The build's tests find Testing/Data by the absolute path of the source tree they were configured in; run from a
# copy of the tree elsewhere, set GLS_SOURCE_LINK to that path and the script links it to this tree.
set -uo pipefail
cd "$(dirname "$0")/../.."
build="${1:-build-gpu}"
logs="${2:-.}"
mkdir -p "$logs"
if [ -n "${GLS_SOURCE_LINK:-}" ] && [ ! -e "$GLS_SOURCE_LINK" ]; then
  mkdir -p "$(dirname "$GLS_SOURCE_LINK")" && ln -s "$PWD" "$GLS_SOURCE_LINK"
fi
status=0
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv | tee "$logs/gpu.txt"
echo "== tests labelled cuda"
"$build/bin/glsCoreTests" --gtest_filter='CudaDevice.*:Backends.*' 2>&1 | tee "$logs/cuda-tests.log" || status=1
echo "== the whole core suite"
"$build/bin/glsCoreTests" --gtest_brief=1 2>&1 | tee "$logs/core-tests.log" || status=1
echo "== GPU benchmark"
{
  "$build/bin/glsCudaBenchmark" --points 1000000,10000000 --exact-up-to 1000000 --repeat 3 &&
    "$build/bin/glsCudaBenchmark" --model rocker-arm.obj --points 1000000 --repeat 3
} 2>&1 | tee "$logs/cuda-benchmark.log" || status=1
echo "== compute-sanitizer memcheck"
if command -v compute-sanitizer >/dev/null; then
  timeout 240 compute-sanitizer --tool memcheck --error-exitcode 3 "$build/bin/glsCoreTests" \
    --gtest_filter='CudaDevice.ChunkedRuns*' 2>&1 | tail -20 | tee "$logs/memcheck.log" || status=1
else
  echo "compute-sanitizer not found" | tee "$logs/memcheck.log"
fi
exit $status
