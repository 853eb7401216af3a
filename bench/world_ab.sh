#!/usr/bin/env bash
# Old binary against new, every mode on three scenes, the same seeds and sizes: the A/B image verdict
# (build/image_ab: src/eval/ab.h, identical / rounding / changed) per configuration, and the speed of each mode
# on the default scene, the two binaries alternating. Not a test: the numbers go to docs/bench/.
#
#   bash bench/world_ab.sh OLD_WORKBENCH NEW_WORKBENCH IMAGE_AB OUT_DIR [SIZE] [SPP] [SEEDS]
#
# Each binary renders with its own shaders (those of its checkout). Prints a Markdown table.
set -euo pipefail
old=$1 new=$2 ab=$3 out=$4 size=${5:-128x128} spp=${6:-16} seeds=${7:-4}
shared=$(cd "$(dirname "$0")/../.." && pwd)/shared
mkdir -p "$out"

scenes=("default::" "helmet::$shared/assets/gltf/DamagedHelmet/DamagedHelmet.gltf"
        "cornell::$shared/reference/cornell.gltf")
# name|flags for both binaries|flags for the new one only (the old one has no such meaning)
configs=("pathtrace|--mode pathtrace|" "hybrid|--mode hybrid|" "reflections|--mode reflections|"
         "hybrid, both --sun-angle 0.53|--mode hybrid --sun-angle 0.53|"
         "reflections, both --sun-angle 0.53|--mode reflections --sun-angle 0.53|"
         "hybrid, old --sun-angle 0|--mode hybrid --sun-angle 0|OLDONLY"
         "pathtrace, new --sun-angle 0.53|--mode pathtrace|--sun-angle 0.53")

render() {  # binary, scene path, flags..., out file
  local bin=$1 scene=$2 file=$3
  shift 3
  # shellcheck disable=SC2086
  "$bin" render ${scene:+"$scene"} --size "$size" --spp "$spp" "$@" --out "$file" >/dev/null 2>&1
}

echo "| scene | configuration | verdict | RMSE | relative MSE | max abs diff | pixels changed | mean shift significant |"
echo "|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  sname=${s%%::*} spath=${s#*::}
  for c in "${configs[@]}"; do
    IFS='|' read -r cname both extra <<<"$c"
    tag=$(echo "$sname-$cname" | tr -c 'a-zA-Z0-9\n' '_')
    pairs=()
    for ((k = 1; k <= seeds; k++)); do
      if [[ $extra == OLDONLY ]]; then
        # shellcheck disable=SC2086
        render "$old" "$spath" "$out/$tag-old-$k.exr" $both --seed "$k"
        # shellcheck disable=SC2086
        render "$new" "$spath" "$out/$tag-new-$k.exr" ${both/--sun-angle 0/} --seed "$k"
      else
        # shellcheck disable=SC2086
        render "$old" "$spath" "$out/$tag-old-$k.exr" $both --seed "$k"
        # shellcheck disable=SC2086
        render "$new" "$spath" "$out/$tag-new-$k.exr" $both $extra --seed "$k"
      fi
      pairs+=("$out/$tag-old-$k.exr" "$out/$tag-new-$k.exr")
    done
    j=$("$ab" "${pairs[@]}")
    echo "$j" >"$out/$tag.json"
    python3 - "$sname" "$cname" "$j" <<'EOF'
import json, sys
s, c, j = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
print(f"| {s} | {c} | {j['verdict']} | {j['rmse']:.3g} | {j['rel_mse']:.3g} | {j['max_abs_diff']:.3g} | "
      f"{100 * j['changed_pixel_fraction']:.1f}% | {'yes' if j['mean_shift_significant'] else 'no'} |")
EOF
  done
done

echo
echo "Speed, default scene, $size, $spp spp, old and new alternating (seconds per frame after the first, per run):"
echo
echo "| mode | old | new | new / old (median) |"
echo "|---|---|---|---|"
for m in pathtrace hybrid reflections; do
  o=() n=()
  for r in 1 2 3 4 5; do
    "$old" render --mode "$m" --size "$size" --spp "$spp" --seed 1 --out "$out/speed.exr" \
      --stats "$out/speed-old.json" >/dev/null 2>&1
    o+=("$(python3 -c "import json;print(json.load(open('$out/speed-old.json'))['seconds_per_frame_after_first'])")")
    "$new" render --mode "$m" --size "$size" --spp "$spp" --seed 1 --out "$out/speed.exr" \
      --stats "$out/speed-new.json" >/dev/null 2>&1
    n+=("$(python3 -c "import json;print(json.load(open('$out/speed-new.json'))['seconds_per_frame_after_first'])")")
  done
  python3 - "$m" "${o[*]}" "${n[*]}" <<'EOF'
import statistics, sys
m, o, n = sys.argv[1], [float(x) for x in sys.argv[2].split()], [float(x) for x in sys.argv[3].split()]
fmt = lambda v: " ".join(f"{x:.4f}" for x in v)
print(f"| {m} | {fmt(o)} | {fmt(n)} | {statistics.median(n) / statistics.median(o):.3f} |")
EOF
done
