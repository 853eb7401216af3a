#!/usr/bin/env bash
# Shader execution reordering against none on a GPU (issue 29, docs/bench/roofline.md): what the device says
# of VK_NV_ray_tracing_invocation_reorder, a render with it under the validation layer, then `render --stats`
# with WB_INVOCATION_REORDER=0, =1 and =1 with the material as the hint (`--define WB_INVOCATION_REORDER=2`)
# alternating (ROUNDS rounds) on the default scene at 512x512 and
# 2048x2048 and the sunlit glossy scene at 256x256 and 2048x2048: milliseconds per sample, rays per second,
# the ratio, and whether the images' means agree. Not a test: run it where the bundle is unpacked
# (docs/GPU.md). `QUICK=1` is a smoke run (small sizes; on lavapipe both arms run without reordering).
#
#   bash bench/gpu_reorder_ab.sh [OUT]          B=.gpu/bin/workbench ROUNDS=3
set -euo pipefail
out=${1:-out/reorder}
wb=${B:-.gpu/bin/workbench}
rounds=${ROUNDS:-3}
repo=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
sunlit="$repo/assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5"
cases=("default|512x512|64|" "default|2048x2048|16|" "sunlit|256x256|1024|$sunlit" "sunlit|2048x2048|16|$sunlit")
[ "${QUICK:-0}" = 1 ] && cases=("default|64x64|8|" "sunlit|64x64|8|$sunlit")

echo "== $(date -u +%FT%TZ) $(uname -n)"
WB_VALIDATION=1 WB_INVOCATION_REORDER=1 "$wb" render --size 128x128 --spp 4 --out "$out/validation.exr" \
  --stats "$out/validation.json" > "$out/validation.log" 2>&1 && echo "validation render: exit 0" ||
  echo "validation render: FAILED ($(tail -2 "$out/validation.log"))"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print('device', j['device'], '|', j['driver'], \
'| invocation_reorder', j['invocation_reorder'], '| used', j['invocation_reorder_used'])" "$out/validation.json"
grep -i "validation" "$out/validation.log" | head -5 || true
WB_VALIDATION=1 WB_INVOCATION_REORDER=1 "$wb" render --define WB_INVOCATION_REORDER=2 --size 128x128 --spp 4 \
  --out "$out/validation2.exr" > "$out/validation2.log" 2>&1 && echo "validation render, material hint: exit 0" ||
  echo "validation render, material hint: FAILED ($(tail -2 "$out/validation2.log"))"

: > "$out/runs.tsv"
for ((r = 1; r <= rounds; r++)); do
  for c in "${cases[@]}"; do
    IFS='|' read -r scene size spp args <<< "$c"
    for reorder in 0 1 2; do
      tag="$scene-$size-$reorder-$r"
      hint=()
      [ "$reorder" = 2 ] && hint=(--define WB_INVOCATION_REORDER=2)  # the material as the hint
      # shellcheck disable=SC2086
      if WB_INVOCATION_REORDER=$((reorder > 0)) "$wb" render $args "${hint[@]}" --size "$size" --spp "$spp" --seed "$r" \
          --out "$out/$tag.exr" --stats "$out/$tag.json" > "$out/$tag.log" 2>&1; then
        printf '%s\t%s\t%s\t%s\t%s\n' "$scene" "$size" "$reorder" "$r" "$out/$tag.json" >> "$out/runs.tsv"
      else
        echo "   $tag failed: $(tail -1 "$out/$tag.log")"
      fi
    done
  done
done
python3 - "$out/runs.tsv" <<'PY'
import json, sys, statistics
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1]) if l.strip()]
by = {}
for scene, size, reorder, r, path in rows:
    j = json.load(open(path))
    spp = j["spp"] if "spp" in j else j["parameters"]["spp"]
    by.setdefault((scene, size), {}).setdefault(reorder, []).append(
        (1000 * j["seconds"] / spp, j["rays_per_second"], j["mean_rgb"], j["invocation_reorder_used"]))
print("| scene | size | arm | ms/sample | vs off | Mrays/s | used | mean rel. diff to off |")
print("|---|---|---|---|---|---|---|---|")
names = {"0": "off", "1": "reorder", "2": "reorder + material hint"}
for (scene, size), arms in by.items():
    off = arms.get("0", [])
    if not off:
        continue
    m0 = statistics.median(x[0] for x in off)
    for arm in sorted(arms):
        on = arms[arm]
        m1 = statistics.median(x[0] for x in on)
        r1 = statistics.median(x[1] for x in on) / 1e6
        diff = max(abs(a - b) / max(abs(a), 1e-12) for x, y in zip(off, on) for a, b in zip(x[2], y[2]))
        print(f"| {scene} | {size} | {names[arm]} | {m1:.3f} | {m1 / m0:.3f} | {r1:.0f} | {on[0][3]} | {diff:.2e} |")
PY
