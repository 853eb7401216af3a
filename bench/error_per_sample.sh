#!/usr/bin/env bash
# Error per sample and efficiency against Blender Cycles (issue 20), per change, on the device the workbench
# picks (lavapipe here; on a GPU machine set up as the README's "Running on a real GPU" says, and pass -b
# .gpu/workbench). Writes OUT/summary.md (and the converge reports it is made from):
#  1. Cornell box (../shared/reference), 256x256, 64 bounces: `converge` against cornell_cycles.exr up to 128 spp,
#     3 runs (seeds), one configuration per change (below, each with the flags that turn later changes off):
#     relMSE at 16/32/64/128 spp, spp and seconds to relMSE 0.01 (log-log interpolated), beside Cycles' figures.
#  2. Efficiency 1 / (relMSE x seconds per sample), with the seconds from alternating timing renders of every
#     configuration (ROUNDS rounds, median seconds per frame after the first, at TIME_SIZE: on a GPU 256x256 is
#     too small to time, so pass e.g. -t 1024x1024 there; the relMSE is taken at 64 spp, 256x256).
#  3. The default scene at 128x128: `converge` of the configuration before issue 20 against the default one for S
#     seconds each (3 runs), against a cached 2048-spp reference; and the hard cases (NaN/Inf, furnaces).
#   bash bench/error_per_sample.sh [-b BIN] [-o OUT] [-r ROUNDS] [-t TIME_SIZE] [-s SECONDS] [-c 'NAME|FLAGS']...
#     [--old-bin BIN]
# -c adds a configuration to sections 1 and 2 (e.g. -c 'ratio2|--define WB_EMITTER_SOLID_ANGLE_RATIO=2.0').
# --old-bin adds a configuration "main" rendered by another binary (e.g. a build of the commit before the
# changes), which is the real "before": the "before" configuration here keeps two small changes that cannot be
# turned off (the light point's dimensions and the BRDF lobe choice, see docs/reports/error_per_sample.md).
# Needs python3 for the summary.
set -euo pipefail
wb=build/workbench
old=""
out=out/error_per_sample
rounds=5
time_size=256x256
seconds=30
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    -b) wb=$2; shift 2 ;;
    -o) out=$2; shift 2 ;;
    -r) rounds=$2; shift 2 ;;
    -t) time_size=$2; shift 2 ;;
    -s) seconds=$2; shift 2 ;;
    -c) extra+=("$2"); shift 2 ;;
    --old-bin) old=$2; shift 2 ;;
    *) echo "usage: bash bench/error_per_sample.sh [-b BIN] [-o OUT] [-r ROUNDS] [-t TIME_SIZE] [-s SECONDS] [-c 'NAME|FLAGS']... [--old-bin BIN]" >&2; exit 2 ;;
  esac
done
repo=$(cd "$(dirname "$0")/.." && pwd)
shared=${WB_SHARED_DIR:-$repo/../shared}
ref=$shared/reference
mkdir -p "$out"
out=$(realpath "$out")
cornell=(--size 256x256 --env-color 0,0,0 --max-bounces 64)

# name|flags, in the order the changes landed (docs/reports/error_per_sample.md): the sampler, Russian roulette on
# sqrt(throughput) from bounce 3, the first solid-angle light sampling (the previous default), the streamlined one
# with the centroid rule (the default).
configs=(
  "before|--sampler sobol --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0"
  "owen|--sampler owen --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0"
  "owen+rr|--define WB_EMITTER_SOLID_ANGLE=0"
  "previous|--define WB_EMITTER_SOLID_ANGLE=1"
  "default|"
  ${extra[@]+"${extra[@]}"}
)

echo "== 1. Cornell box: error per sample ($(date -u +%FT%TZ), $(uname -n))"
args=()
for c in "${configs[@]}"; do args+=(--config "${c%%|*}:${c#*|}"); done
"$wb" converge "$ref/cornell.gltf" "${cornell[@]}" --reference "$ref/cornell_cycles.exr" --seconds 3600 \
  --max-spp 128 --runs 3 --target-relmse 0.01 "${args[@]}" --out "$out/cornell"
if [ -n "$old" ]; then
  "$old" converge "$ref/cornell.gltf" "${cornell[@]}" --reference "$ref/cornell_cycles.exr" --seconds 3600 \
    --max-spp 128 --runs 3 --target-relmse 0.01 --config "main:" --out "$out/cornell_main"
fi

echo "== 2. Efficiency: alternating timing renders at $time_size, $rounds rounds"
: > "$out/timing.txt"
for r in $(seq 1 "$rounds"); do
  for c in "${configs[@]}" ${old:+"main|"}; do
    name=${c%%|*}
    read -r -a flags <<< "${c#*|}"
    bin=$wb
    [ "$name" = main ] && bin=$old
    "$bin" render "$ref/cornell.gltf" --size "$time_size" --env-color 0,0,0 --max-bounces 64 --spp 16 \
      --seed "$r" "${flags[@]}" --out "$out/timing.exr" --stats "$out/timing.json" > /dev/null
    python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(sys.argv[2], j['seconds_per_frame_after_first'], j['device'])" \
      "$out/timing.json" "$name" >> "$out/timing.txt"
  done
done

echo "== 3. Default scene and hard cases"
"$wb" converge --size 128x128 --seconds "$seconds" --runs 3 --reference-spp 2048 \
  --config "before:--sampler sobol --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0" \
  --config "default:" --out "$out/default_scene"
"$wb" converge --hard-cases --size 48x48 --spp 64 --out "$out/hard_cases"

python3 - "$out" "$ref/cornell_cycles_low_spp.json" <<'EOF'
import csv, json, math, os, statistics, sys
out = sys.argv[1]
cycles = json.load(open(sys.argv[2]))["spp"]
rows = {}
for sub in ("cornell", "cornell_main"):
    path = os.path.join(out, sub, "converge.csv")
    if os.path.exists(path):
        for r in csv.DictReader(open(path)):
            rows.setdefault(r["config"], []).append(r)
times = {}
device = ""
for line in open(os.path.join(out, "timing.txt")):
    name, sec, *dev = line.split(maxsplit=2)
    times.setdefault(name, []).append(float(sec))
    device = dev[0].strip() if dev else device

def at(rs, spp, key):
    for r in rs:
        if int(r["spp"]) == spp:
            return float(r[key])
    return float("nan")

def to_target(rs, key, target=0.01):  # log-log interpolation of `key` (spp or seconds) at relMSE = target
    pts = [(float(r[key]), float(r["relmse"])) for r in rs if float(r[key]) > 0]
    for (x0, e0), (x1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e0 > e1:
            t = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(x0) + t * (math.log(x1) - math.log(x0)))
    return float("nan")

lines = ["# Error per sample on the Cornell box against Cycles (bench/error_per_sample.sh)", "",
         f"Device: {device}. relMSE (eps 0.01) against cornell_cycles.exr, 256x256, 64 bounces, mean of 3 runs.",
         "Efficiency = 1 / (relMSE at 64 spp x seconds per sample), seconds per sample = median seconds per frame of "
         "the alternating timing renders (at the timing size).", "",
         "| config | 16 spp | 32 spp | 64 spp | 128 spp | spp to 0.01 | s to 0.01 (converge) | s/sample (timing) | efficiency |",
         "|---|---|---|---|---|---|---|---|---|",
         "| Cycles 3.4 (CPU) | %.4f | %.4f | %.4f | %.4f | %d | | | |" % (
             cycles["16"]["relmse_mean"], cycles["32"]["relmse_mean"], cycles["64"]["relmse_mean"],
             cycles["128"]["relmse_mean"], 31)]
for name, rs in rows.items():
    sec = statistics.median(times[name]) if name in times else float("nan")
    eff = 1.0 / (at(rs, 64, "relmse") * sec) if sec == sec else float("nan")
    lines.append("| %s | %.4f | %.4f | %.4f | %.4f | %.1f | %.3g | %.4g | %.4g |" % (
        name, at(rs, 16, "relmse"), at(rs, 32, "relmse"), at(rs, 64, "relmse"), at(rs, 128, "relmse"),
        to_target(rs, "spp"), to_target(rs, "seconds"), sec, eff))
lines += ["", "Timing renders (seconds per frame after the first, per round):", ""]
for name, ts in times.items():
    lines.append(f"- {name}: " + " ".join("%.4g" % t for t in ts))
lines += ["", "Default scene (128x128, converge): see default_scene/converge.md; hard cases: hard_cases/hard_cases.md.", ""]
open(os.path.join(out, "summary.md"), "w").write("\n".join(lines))
print("\n".join(lines))
EOF
