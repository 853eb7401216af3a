#!/usr/bin/env bash
# Issue 29's GPU candidates in one batch (docs/bench/roofline.md): the roofline, then each candidate switch
# against the default build in alternating runs, then error per sample on the sunlit glossy scene. Not a test:
# the numbers go to docs/bench/. On a GPU machine set up as docs/GPU.md says:
#
#   bash bench/gpu_ab.sh [-b BIN] [-o OUT] [-r ROUNDS] [-q]
#
#  1. `bench --only pathtracer` at 512x512 with the roofline at 256x256 and 2048x2048 (bench_pathtracer.json).
#  2. ROUNDS rounds (default 3); in each, every configuration below renders the default scene and the sunlit
#     glossy scene at 256x256 and 2048x2048 one after another (`render --stats`, enough samples for ~0.5 s of
#     tracing on an H200): wall seconds per sample (the first batch left out) and rays per second.
#  3. `converge` on the sunlit glossy scene, 256x256, against a 4096-spp reference, 3 runs each: the default
#     (reflector guiding at fraction 0.3), no guiding, fraction 0.5 and the device's samples per launch; and on the Cornell box
#     against ../shared's Cycles reference (WB_SHARED_DIR), default and samples per launch: relMSE per spp and
#     seconds to relMSE 0.01 (timed on the runs after the first, which traces one sample per submission).
# -q: a smoke run (one round, 64x64 and 128x128, few samples: a few minutes on lavapipe). Prints OUT/summary.md (Markdown) and
# writes OUT/summary.json. Needs python3.
set -euo pipefail
wb=build/workbench
out=out/gpu_ab
rounds=3
quick=0
while [ $# -gt 0 ]; do
  case $1 in
    -b) wb=$2; shift 2 ;;
    -o) out=$2; shift 2 ;;
    -r) rounds=$2; shift 2 ;;
    -q) quick=1; rounds=1; shift ;;
    *) echo "usage: bash bench/gpu_ab.sh [-b BIN] [-o OUT] [-r ROUNDS] [-q]" >&2; exit 2 ;;
  esac
done
repo=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/runs"
out=$(realpath "$out")
sunlit=("$repo/assets/sunlit_spheres.gltf" --env-color 0.2,0.3,0.5)

# name|render flags: the default build first; each other one switches one candidate.
configs=(
  "default|"
  "launch16|--samples-per-launch 16"
  "launch-auto|--samples-per-launch 0"
  "payload+128B|--define WB_PAYLOAD_PAD_VEC4=8"
  "no-guiding|--define WB_REFLECTOR_GUIDING=0"
)
# name|scene arguments
scenes=("default|" "sunlit|${sunlit[*]}")
# size|spp per run
sizes=("256x256|1024" "2048x2048|16")
[ "$quick" = 1 ] && sizes=("64x64|16" "128x128|4")

echo "== 1. roofline ($(date -u +%FT%TZ), $(uname -n))"
if [ "$quick" = 1 ]; then
  "$wb" bench --only pathtracer --quick --roofline-sizes 64x64 --out "$out/bench_pathtracer.json"
else
  "$wb" bench --only pathtracer --size 512x512 --roofline-sizes 256x256,2048x2048 --repeats 3 \
    --out "$out/bench_pathtracer.json"
fi

echo "== 2. candidates, $rounds alternating rounds"
: > "$out/timing.tsv"
for ((r = 1; r <= rounds; r++)); do
  for s in "${scenes[@]}"; do
    sname=${s%%|*}
    read -r -a sargs <<< "${s#*|}"
    for z in "${sizes[@]}"; do
      size=${z%%|*} spp=${z#*|}
      for c in "${configs[@]}"; do
        cname=${c%%|*}
        read -r -a flags <<< "${c#*|}"
        tag="$sname-$size-$cname-$r"
        if "$wb" render ${sargs[@]+"${sargs[@]}"} --size "$size" --spp "$spp" --seed "$r" \
            ${flags[@]+"${flags[@]}"} --out "$out/runs/$tag.exr" --stats "$out/runs/$tag.json" \
            > "$out/runs/$tag.log" 2>&1; then
          printf '%s\t%s\t%s\t%s\t%s\n' "$sname" "$size" "$cname" "$r" "$out/runs/$tag.json" >> "$out/timing.tsv"
        else
          printf '%s\t%s\t%s\t%s\tFAILED\n' "$sname" "$size" "$cname" "$r" >> "$out/timing.tsv"
          echo "   $tag failed: $(tail -1 "$out/runs/$tag.log")"
        fi
      done
    done
  done
done

echo "== 3. error per sample on the sunlit glossy scene"
csize=256x256 cref=4096 cspp=256
[ "$quick" = 1 ] && csize=64x64 cref=256 cspp=16
"$wb" converge "${sunlit[@]}" --size "$csize" --reference-spp "$cref" --seconds 3600 --max-spp "$cspp" --runs 3 \
  --target-relmse 0.01 --config "default:" --config "no-guiding:--define WB_REFLECTOR_GUIDING=0" \
  --config "guiding0.5:--define WB_REFLECTOR_FRACTION=0.5" \
  --config "launch-auto:--samples-per-launch 0" --out "$out/sunlit_converge"
shared=${WB_SHARED_DIR:-$repo/../shared}
if [ -f "$shared/reference/cornell_cycles.exr" ]; then
  "$wb" converge "$shared/reference/cornell.gltf" --size "$csize" --env-color 0,0,0 --max-bounces 64 \
    --reference "$shared/reference/cornell_cycles.exr" --seconds 3600 --max-spp "$((cspp < 128 ? cspp : 128))" --runs 3 --target-relmse 0.01 \
    --config "default:" --config "launch-auto:--samples-per-launch 0" --out "$out/cornell_converge"
else
  echo "   $shared/reference/cornell_cycles.exr not found (set WB_SHARED_DIR): no Cornell box convergence"
fi

python3 - "$out" <<'EOF'
import csv, json, math, os, statistics, sys
out = sys.argv[1]
runs = {}
for line in open(os.path.join(out, "timing.tsv")):
    scene, size, config, rnd, path = line.rstrip("\n").split("\t")
    key = (scene, size)
    if path == "FAILED":
        runs.setdefault(key, {}).setdefault(config, None)
        continue
    j = json.load(open(path))
    frames = j["frame_seconds"]
    # Each batch's time is shared equally by its samples: drop the first batch (pipeline warm-up).
    first = frames[0]
    k = 1
    while k < len(frames) and frames[k] == first:
        k += 1
    rest = frames[k:] if k < len(frames) else frames
    sec = sum(rest) / len(rest)
    entry = runs.setdefault(key, {}).setdefault(config, {"s": [], "rays": [], "device": j["device"]})
    if entry is None:
        continue
    entry["s"].append(sec)
    entry["rays"].append(j["rays"] / j["spp"] / sec)

device = next((e["device"] for k in runs.values() for e in k.values() if e), "?")
lines = ["# GPU candidates, alternating runs (bench/gpu_ab.sh)", "", f"Device: {device}.", "",
         "| scene | size | config | ms/sample (median) | rays/s | vs default (time) |", "|---|---|---|---|---|---|"]
summary = {"device": device, "timing": []}
for (scene, size), configs in runs.items():
    base = configs.get("default")
    bt = statistics.median(base["s"]) if base else float("nan")
    for name, e in configs.items():
        if e is None:
            lines.append(f"| {scene} | {size} | {name} | failed | | |")
            summary["timing"].append({"scene": scene, "size": size, "config": name, "failed": True})
            continue
        t = statistics.median(e["s"])
        rays = statistics.median(e["rays"])
        lines.append(f"| {scene} | {size} | {name} | {1e3 * t:.4g} | {rays:.4g} | {t / bt:.3f} |")
        summary["timing"].append({"scene": scene, "size": size, "config": name, "seconds_per_sample": t,
                                  "rays_per_second": rays, "time_vs_default": t / bt,
                                  "seconds_per_sample_runs": e["s"]})
bench = json.load(open(os.path.join(out, "bench_pathtracer.json")))
lines += ["", "Roofline (`bench --only pathtracer`, GPU time):", "",
          "| scene | size | bare primary rays/s | bare diffuse rays/s | path tracer rays/s | ratio |", "|---|---|---|---|---|---|"]
summary["roofline"] = []
for r in bench.get("pathtracer", []):
    if "pathtracer_vs_bare_diffuse_ratio" not in r:
        continue
    lines.append("| %s | %s | %.4g | %.4g | %.4g | %.3f |" % (
        r["scene"], r["size"], r["bare_primary_rays_per_second"], r["bare_diffuse_rays_per_second"],
        r["pathtracer_gpu_rays_per_second"], r["pathtracer_vs_bare_diffuse_ratio"]))
    summary["roofline"].append({k: r[k] for k in ("scene", "size", "bare_primary_rays_per_second",
                                                  "bare_diffuse_rays_per_second", "pathtracer_gpu_rays_per_second",
                                                  "pathtracer_vs_bare_diffuse_ratio")})
for sub, title in (("sunlit_converge", "Sunlit glossy scene"), ("cornell_converge", "Cornell box (against Cycles)")):
    conv = os.path.join(out, sub, "converge.md")
    if os.path.exists(conv):
        lines += ["", f"{title}, error per sample and time to relMSE 0.01 (converge):", "", open(conv).read()]
open(os.path.join(out, "summary.md"), "w").write("\n".join(lines) + "\n")
json.dump(summary, open(os.path.join(out, "summary.json"), "w"), indent=1)
print("\n".join(lines))
EOF
