#!/usr/bin/env bash
# Hot reload as the live window shows it: the workbench window (under xvfb-run on a machine without a display)
# renders the default scene from a private copy of shaders/ while a script makes N real code edits of the
# closest-hit shader (a different constant, as `bench --only reload` does with `watch`), two seconds apart.
# Prints one JSON object: per-edit latencies and the window's frame times around each reload (frames here
# include the ImGui panel and the present; the window traces within a time budget, a tenth of it while a
# rebuild compiles on a CPU device).
#   bash bench/window_reload.sh [build/workbench] [N=20] > docs/bench/lavapipe_window_reload.json
set -euo pipefail
wb=$(realpath "${1:-build/workbench}")
edits=${2:-20}
root=$(mktemp -d)
trap '[ -n "${WB_KEEP:-}" ] || rm -rf "$root"' EXIT
cp -r "$(dirname "$0")/../shaders" "$(dirname "$0")/../assets" "$root/"
mkdir -p "$root/shader_cache" "$root/edits"
chit=$root/shaders/pathtracer/closesthit.rchit
grep -q 'const float minCos = 1e-3;' "$chit"
{
  echo "wait_samples 4 120"
  echo "frames 60"
  for i in $(seq 1 "$edits"); do
    value=$(python3 -c "print('%.9g' % (1e-3 * (1 + 1e-4 * $i)))")
    sed "s/const float minCos = 1e-3;/const float minCos = $value;/" "$chit" >"$root/edits/$i.rchit"
    echo "copy $root/edits/$i.rchit $chit"
    echo "wait_reload 30"
    echo "frames 40"
  done
  echo "stats $root/stats.json"
  echo "quit"
} >"$root/script.txt"
if [ -z "${DISPLAY:-}" ]; then run=(xvfb-run -a -s "-screen 0 1920x1080x24"); else run=(); fi
WB_ROOT=$root WB_SHADER_CACHE_DIR=$root/shader_cache "${run[@]}" "$wb" --script "$root/script.txt" \
  >"$root/out.txt" 2>&1 || { cat "$root/out.txt" >&2; exit 1; }
[ -n "${WB_KEEP:-}" ] && echo "kept $root" >&2
python3 - "$root/stats.json" "$wb" "$edits" <<'PY'
import json, platform, subprocess, sys, datetime
s = json.load(open(sys.argv[1]))
ev = [r for r in s["reloads"] if r["ok"] and any(f.endswith("closesthit.rchit") for f in r["files_changed"])]
def pct(v, p):
    v = sorted(v)
    return v[min(len(v) - 1, int(p * (len(v) - 1) + 0.5))] if v else None
slow = [max(r["frame_ms_max_during_rebuild"], r["first_new_frame_ms"]) / r["frame_ms_median_before"] for r in ev]
ctrl = [r["frame_ms_max_before_same_span"] / r["frame_ms_median_before"] for r in ev]
e2f = [r["edit_to_first_frame_ms"] for r in ev if r["edit_to_first_frame_ms"] is not None]
out = {
    "command": "bash bench/window_reload.sh " + " ".join(sys.argv[2:]),
    "date": datetime.datetime.utcnow().strftime("%Y-%m-%dT%H:%M:%SZ"),
    "machine": {"cores": __import__("os").cpu_count(), "kernel": platform.release()},
    "window": {"size": [s["window_width"], s["window_height"]], "trace_size": [s["trace_width"], s["trace_height"]],
               "trace_budget_ms": s["trace_budget_ms"], "present_mode": s["present_mode"]},
    "edits": len(ev),
    "edit_to_first_frame_ms_p50": pct(e2f, 0.5), "edit_to_first_frame_ms_p95": pct(e2f, 0.95),
    "edit_to_new_pipeline_ms_p50": pct([r["edit_to_new_pipeline_ms"] for r in ev], 0.5),
    "frame_ms_median_before_edit": pct([r["frame_ms_median_before"] for r in ev], 0.5),
    "frame_ms_max_during_rebuild_median": pct([r["frame_ms_max_during_rebuild"] for r in ev], 0.5),
    "first_new_frame_ms_median": pct([r["first_new_frame_ms"] for r in ev], 0.5),
    # Frames drawn from the edit to the first new frame, per second of that span: how often the window
    # still updates while it rests for a rebuild.
    "frames_per_second_during_rebuild_median": pct([r["frames_during_rebuild"] * 1000.0 / r["edit_to_first_frame_ms"]
                                                    for r in ev if r["edit_to_first_frame_ms"]], 0.5),
    "slowest_frame_vs_before_p50": pct(slow, 0.5), "slowest_frame_vs_before_max": pct(slow, 1.0),
    "slowest_frame_vs_before_per_edit": slow,
    "control_slowest_frame_vs_before_p50": pct(ctrl, 0.5), "control_slowest_frame_vs_before_max": pct(ctrl, 1.0),
    "driver": "lavapipe unless VK_DRIVER_FILES says otherwise: " + __import__("os").environ.get("VK_DRIVER_FILES", "(unset)"),
    "validation_errors": s["validation_errors"],
}
print(json.dumps(out, indent=2))
PY
