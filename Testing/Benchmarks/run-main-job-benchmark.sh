#!/usr/bin/env bash
# The main job at scale (docs/performance.md, "The main job at scale"): M1 and M3 for each model, side by side with
# L1 in the same run. Each model is sampled by area to POINTS points and written as a binary float PLY with positions
# only (glsSampleMesh); then L1 (the fused features alone, glsLargeScanBenchmark --case L1), the normals alone (M3,
# --case normals) and the main job end to end (M1: with --no-directions, the path M1's targets were set for; M1d: by
# default, with the principal directions' fused pass) run one after the other, the main job under /usr/bin/time for
# its peak resident memory, and the output's bytes per point are measured; the default run's result is then written
# as .vtp, .las and .ply in turn (output_formats.py).
#   Testing/Benchmarks/run-main-job-benchmark.sh [build dir (build)] [points (10000000)] [models (bunny rocker-arm)]
set -euo pipefail
build="${1:-build}"
points="${2:-10000000}"
models="${3:-bunny rocker-arm}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for model in $models; do
  ply="$work/$model-$points.ply"
  "$build/bin/glsSampleMesh" "$model" "$points" "$ply"
  l1=$("$build/bin/glsLargeScanBenchmark" --case L1 --models "$model" --points "$points" | tee >(cat >&2) |
    awk -v m="$model" '$1 == m { print $2; exit }')
  normals=$("$build/bin/glsLargeScanBenchmark" --case normals --models "$model" --points "$points" | tee >(cat >&2) |
    awk -v m="$model" '$1 == m { print $2; exit }')
  for variant in --no-directions default; do
    flag=""
    [ "$variant" = default ] || flag="$variant"
    start=$(date +%s.%N)
    /usr/bin/time -f '%M' -o "$work/rss" "$build/bin/gls-analyze" "$ply" --output-dir "$work/out" $flag \
      > "$work/log" 2>&1 || { cat "$work/log"; exit 1; }
    end=$(date +%s.%N)
    vtp="$work/out/$model-$points-gls.vtp"
    awk -v m="$model" -v n="$points" -v l1="$l1" -v nr="$normals" -v t0="$start" -v t1="$end" -v v="$variant" \
        -v rss="$(cat "$work/rss")" -v bytes="$(stat -c %s "$vtp")" 'BEGIN {
      t = t1 - t0;
      if (v == "default") {
        printf "M1d %s %d points: main job with the principal directions %.1f s (L1 %s s: %.2fx), peak %.0f MiB, " \
               "output %.1f bytes per point\n", m, n, t, l1, (l1 > 0 ? t / l1 : 0), rss / 1024, bytes / n;
      } else {
        printf "M1 %s %d points: main job --no-directions %.1f s (L1 %s s: %.2fx, target <= 2), peak %.0f MiB " \
               "(target <= 4096), output %.1f bytes per point (target <= 40)\n", m, n, t, l1, (l1 > 0 ? t / l1 : 0),
               rss / 1024, bytes / n;
        printf "M3 %s %d points: normals %s s (L1 %s s: %.2fx, target <= 0.33)\n", m, n, nr, l1,
               (l1 > 0 ? nr / l1 : 0) } }'
    grep -E "^(normals|GLS pipeline|principal directions|denoising|wrote the data|memory)" "$work/log"
    if [ "$variant" = default ]; then  # the same result written as .vtp, .las and .ply, in turn (docs/performance.md)
      PYTHONPATH="$build/lib/python3/dist-packages" pvpython "$(dirname "$0")/output_formats.py" "$vtp" 2>&1 |
        grep -v L2_NORM_RANGE
    fi
    rm -rf "$work/out"
  done
  rm -rf "$work/out" "$ply"
done
