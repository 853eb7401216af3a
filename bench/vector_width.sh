#!/usr/bin/env bash
# llvmpipe's vector width, 8 lanes (LP_NATIVE_VECTOR_WIDTH=256, Mesa's default with AVX2) against 4 lanes (128,
# the workbench's default, vk/driver_env.h), in alternating rounds: the path tracer's JIT (a cold 8x8 render
# with an empty Mesa cache), its trace rate (384x384, 8 spp, warm), the hybrid renderer at 1280x720, hot reload
# (`bench --only startup reload --edits 10`), and whether the images differ. Prints a Markdown table.
#   bash bench/vector_width.sh [build/workbench] [rounds] > docs/bench/lavapipe_vector_width.md
set -euo pipefail
wb=$(realpath "${1:-build/workbench}")
rounds=${2:-2}
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
out=$root/rows.jsonl
for round in $(seq 1 "$rounds"); do
  for w in 256 128; do
    d=$root/$round-$w
    mkdir -p "$d"
    # Both variables explicit: with a MESA_SHADER_CACHE_DIR of the user's the workbench leaves the width alone.
    export LP_NATIVE_VECTOR_WIDTH=$w
    MESA_SHADER_CACHE_DIR=$d/mesa_cold "$wb" render --size 8x8 --spp 1 --out "$d/cold.png" --stats "$d/cold.json" >/dev/null
    export MESA_SHADER_CACHE_DIR=$root/mesa_$w
    "$wb" render --size 384x384 --spp 8 --out "$d/pt.exr" --stats "$d/pt_warmup.json" >/dev/null
    ref=()
    [ -f "$root/1-256/pt.exr" ] && ref=(--reference "$root/1-256/pt.exr")
    "$wb" render --size 384x384 --spp 8 --out "$d/pt.exr" --stats "$d/pt.json" "${ref[@]}" >/dev/null
    "$wb" render --mode hybrid --size 1280x720 --spp 8 --out "$d/hy.png" --stats "$d/hy.json" >/dev/null
    unset MESA_SHADER_CACHE_DIR
    "$wb" bench --only startup reload --edits 10 --out "$d/bench.json" >/dev/null 2>&1
    python3 - "$d" "$w" "$round" >>"$out" <<'PY'
import json, sys
d, w, r = sys.argv[1:]
j = lambda n: json.load(open(f"{d}/{n}.json"))
pt, b = j("pt"), j("bench")
rl, st = b["hot_reload"], b["startup"]
print(json.dumps({"round": int(r), "width": int(w), "device": pt["device"],
  "cold_render_s": j("cold")["seconds"], "mrays_per_s": pt["rays_per_second"] / 1e6, "rays": pt["rays"],
  "rmse_vs_256": pt.get("error_vs_reference", {}).get("rmse"),
  "hybrid_720p_s_per_frame": j("hy")["seconds_per_frame_after_first"],
  "cold_start_ms": st["cold_to_first_frame_ms"], "warm_start_ms": st["warm_to_first_frame_ms"],
  "edit_to_first_frame_p50": rl["edit_to_first_frame_ms_p50"], "edit_to_first_frame_p95": rl["edit_to_first_frame_ms_p95"],
  "pipeline_ms_median": rl["pipeline_ms_median"], "compile_ms_median": rl["compile_ms_median"],
  "slowest_frame_vs_before_p50": rl["slowest_frame_vs_before_p50"], "slowest_frame_vs_before_max": rl["slowest_frame_vs_before_max"],
  "control_slowest_frame_vs_before_p50": rl["control_slowest_frame_vs_before_p50"]}))
PY
  done
done
python3 - "$out" "$wb" "$rounds" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
cols = [("round", "{}"), ("width", "{}"), ("cold_render_s", "{:.2f}"), ("mrays_per_s", "{:.2f}"), ("rays", "{}"),
        ("rmse_vs_256", "{}"), ("hybrid_720p_s_per_frame", "{:.3f}"), ("cold_start_ms", "{:.0f}"),
        ("warm_start_ms", "{:.0f}"), ("edit_to_first_frame_p50", "{:.0f}"), ("edit_to_first_frame_p95", "{:.0f}"),
        ("pipeline_ms_median", "{:.0f}"), ("compile_ms_median", "{:.0f}"), ("slowest_frame_vs_before_p50", "{:.2f}"),
        ("slowest_frame_vs_before_max", "{:.2f}"), ("control_slowest_frame_vs_before_p50", "{:.2f}")]
print("| " + " | ".join(c for c, _ in cols) + " |")
print("|" + "---|" * len(cols))
for r in rows:
    print("| " + " | ".join(f.format(r[c]) if r[c] is not None else "-" for c, f in cols) + " |")
print(f"\n`bash bench/vector_width.sh {sys.argv[2]} {sys.argv[3]}` on {rows[0]['device'].split(',')[0]}); "
      "width = LP_NATIVE_VECTOR_WIDTH; cold_render_s: `render --size 8x8 --spp 1` with an empty Mesa cache "
      "(the first trace JITs the pipeline); mrays_per_s, rays: `render --size 384x384 --spp 8`, warm; "
      "rmse_vs_256: that image against round 1's 256-bit one; hybrid: `render --mode hybrid --size 1280x720 "
      "--spp 8`; the rest: `bench --only startup reload --edits 10` (ms; 128x128 trace while editing).")
PY
