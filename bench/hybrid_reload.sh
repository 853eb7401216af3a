#!/usr/bin/env bash
# Hot reload of the hybrid renderer's shaders (the reload section of `bench` edits the path tracer's closest-hit):
# `watch --mode reflections` renders the default scene at 128x128 from a private copy of shaders/ while each of
# the four hybrid programs gets three real code edits (a new function in front of main). Prints a Markdown table
# of the watch log (medians per file).
#   bash bench/hybrid_reload.sh [build/workbench] > docs/bench/lavapipe_hybrid_reload.md
set -euo pipefail
wb=$(realpath "${1:-build/workbench}")
root=$(mktemp -d)
trap 'kill $pid 2>/dev/null || true; rm -rf "$root"' EXIT
cp -r "$(dirname "$0")/../shaders" "$(dirname "$0")/../assets" "$root/"
mkdir -p "$root/shader_cache"
WB_ROOT=$root WB_SHADER_CACHE_DIR=$root/shader_cache "$wb" watch --headless --mode reflections --size 128x128 \
  --seconds 120 --log "$root/log.jsonl" >"$root/out.txt" 2>&1 &
pid=$!
for _ in $(seq 1 300); do grep -q watching "$root/out.txt" 2>/dev/null && break; sleep 0.1; done
sleep 1.5
n=0
for round in 1 2 3; do
  for f in shadow_ao.rgen reflect.rchit composite.comp gbuffer.frag; do
    n=$((n + 1))
    sed -i "0,/^void main() {/s//float wbBenchEdit$n() { return $n.0; }\nvoid main() {/" "$root/shaders/hybrid/$f"
    for _ in $(seq 1 150); do [ "$(wc -l <"$root/log.jsonl" 2>/dev/null || echo 0)" -ge $n ] && break; sleep 0.1; done
    sleep 0.5
  done
done
kill $pid
python3 - "$root/log.jsonl" "$wb" <<'PY'
import json, statistics, sys, subprocess
rows = {}
for line in open(sys.argv[1]):
    j = json.loads(line)
    rows.setdefault(j["files_changed"][0].split("/")[-1], []).append(j)
print("| edited file | edits | edit -> new pipeline ms | edit -> first new frame ms | first new frame ms | frame before ms | slowest frame during ms |")
print("|---|---|---|---|---|---|---|")
for f, js in rows.items():
    med = lambda k: statistics.median(j[k] for j in js)
    print(f"| {f} | {len(js)} | {med('edit_to_new_pipeline_ms'):.0f} | {med('edit_to_first_frame_ms'):.0f} | "
          f"{med('first_new_frame_ms'):.0f} | {med('frame_ms_median_before'):.1f} | {med('frame_ms_max_during_rebuild'):.1f} |")
print(f"\nMedians over the edits; `bash bench/hybrid_reload.sh` ({' '.join(sys.argv[2:])}), lavapipe unless VK_DRIVER_FILES says otherwise.")
PY
