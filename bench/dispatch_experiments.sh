#!/usr/bin/env bash
# What the path tracer's rays/s on lavapipe depends on (issue: close the gap to Embree): dispatch shape (tiles),
# llvmpipe thread count, specialised vs generic shaders, payload size, path length. Each row: median of 3 renders of the
# default scene at 512x512, 4 spp, after one warm-up render. Prints a Markdown table.
#   bash bench/dispatch_experiments.sh [build/workbench] > docs/bench/lavapipe_dispatch.md
set -euo pipefail
wb=${1:-build/workbench}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

measure() {  # label, env, flags...
  local label=$1 envs=$2
  shift 2
  local rates=()
  env $envs "$wb" render --size 512x512 --spp 1 --out "$tmp/w.png" "$@" >/dev/null 2>&1
  for _ in 1 2 3; do
    env $envs "$wb" render --size 512x512 --spp 4 --out "$tmp/o.png" --stats "$tmp/s.json" "$@" >/dev/null 2>&1
    rates+=("$(python3 -c "import json; j=json.load(open('$tmp/s.json')); print(j['rays_per_second'], j['paths_per_second'], j['seconds_per_frame'])")")
  done
  printf '%s\n' "${rates[@]}" | sort -n | sed -n 2p | {
    read -r rays paths spf
    printf '| %s | `%s %s` | %.2f | %.2f | %.3f |\n' "$label" "$envs" "$*" "$(python3 -c "print($rays/1e6)")" \
      "$(python3 -c "print($paths/1e6)")" "$spf"
  }
}

echo "Default scene, 512x512, 4 spp per run, median of 3 runs; $(nproc) cores; $(date -u +%Y-%m-%dT%H:%MZ)."
echo
echo "| experiment | env / flags | Mrays/s | Mpaths/s | s per sample |"
echo "|---|---|---|---|---|"
measure "baseline: one dispatch per sample" "WB=1"
measure "tiles 256x256" "WB=1" --tile 256x256
measure "tiles 64x64" "WB=1" --tile 64x64
measure "tiles 16x16" "WB=1" --tile 16x16
measure "rows 512x8" "WB=1" --tile 512x8
measure "LP_NUM_THREADS=1" "LP_NUM_THREADS=1"
measure "LP_NUM_THREADS=4 (2x cores)" "LP_NUM_THREADS=4"
measure "generic shaders (all features)" "WB=1" --generic
measure "max bounces 2" "WB=1" --max-bounces 2
measure "no NEE (no shadow rays)" "WB=1" --no-nee
measure "payload +64 bytes" "WB=1" --define WB_PAYLOAD_PAD_VEC4=4
measure "payload +256 bytes" "WB=1" --define WB_PAYLOAD_PAD_VEC4=16
measure "GALLIVM_PERF=nopt (no LLVM optimisation)" "GALLIVM_PERF=nopt"
