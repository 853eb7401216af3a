#!/usr/bin/env bash
# Old binary against new, every mode on three scenes, the same seeds and sizes: the A/B image verdict
# (build/image_ab: src/eval/ab.h, identical / rounding / changed) per configuration, and the speed of each mode
# on the default scene, the two binaries alternating. Not a test: the numbers go to docs/bench/.
#
#   bash bench/world_ab.sh OLD_WORKBENCH NEW_WORKBENCH IMAGE_AB OUT_DIR [SIZE] [SPP] [SEEDS] [images|speed|all]
#
# Each binary renders with its own shaders (those of its checkout). Prints Markdown tables.
set -euo pipefail
old=$1 new=$2 ab=$3 out=$4 size=${5:-128x128} spp=${6:-16} seeds=${7:-4} what=${8:-all}
shared=$(cd "$(dirname "$0")/../.." && pwd)/shared
mkdir -p "$out"

scenes=("default::" "helmet::$shared/assets/gltf/DamagedHelmet/DamagedHelmet.gltf"
        "cornell::$shared/reference/cornell.gltf")
# name|flags of the old binary|flags of the new one
configs=("pathtrace|--mode pathtrace|--mode pathtrace"
         "hybrid|--mode hybrid|--mode hybrid"
         "reflections|--mode reflections|--mode reflections"
         "hybrid, both --sun-angle 0.53|--mode hybrid --sun-angle 0.53|--mode hybrid --sun-angle 0.53"
         "reflections, both --sun-angle 0.53|--mode reflections --sun-angle 0.53|--mode reflections --sun-angle 0.53"
         "hybrid, old --sun-angle 0|--mode hybrid --sun-angle 0|--mode hybrid"
         "pathtrace, new --sun-angle 0.53|--mode pathtrace|--mode pathtrace --sun-angle 0.53")

render() {  # binary, scene path (empty: the default scene), out file, flags...
  local bin=$1 scene=$2 file=$3
  shift 3
  "$bin" render ${scene:+"$scene"} --size "$size" --spp "$spp" "$@" --out "$file" >/dev/null 2>&1
}

json() {  # file, python expression of j
  python3 -c "import json, sys; j = json.load(open(sys.argv[1])); print($2)" "$1"
}

images() {
  echo "| scene | configuration | verdict | RMSE | relative MSE | max abs diff | pixels changed | mean shift significant |"
  echo "|---|---|---|---|---|---|---|---|"
  local s c k sname spath cname oldFlags newFlags tag
  for s in "${scenes[@]}"; do
    sname=${s%%::*} spath=${s#*::}
    for c in "${configs[@]}"; do
      IFS='|' read -r cname oldFlags newFlags <<<"$c"
      tag=$(echo "$sname-$cname" | tr -c 'a-zA-Z0-9\n' '_')
      local pairs=()
      for ((k = 1; k <= seeds; k++)); do
        # shellcheck disable=SC2086
        render "$old" "$spath" "$out/$tag-old-$k.exr" $oldFlags --seed "$k"
        # shellcheck disable=SC2086
        render "$new" "$spath" "$out/$tag-new-$k.exr" $newFlags --seed "$k"
        pairs+=("$out/$tag-old-$k.exr" "$out/$tag-new-$k.exr")
      done
      "$ab" "${pairs[@]}" >"$out/$tag.json"
      echo "| $sname | $cname | $(json "$out/$tag.json" "' | '.join([j['verdict'], f\"{j['rmse']:.3g}\",
        f\"{j['rel_mse']:.3g}\", f\"{j['max_abs_diff']:.3g}\", f\"{100 * j['changed_pixel_fraction']:.1f}%\",
        'yes' if j['mean_shift_significant'] else 'no'])") |"
    done
  done
}

median() { python3 -c "import statistics, sys; print(statistics.median(float(x) for x in sys.argv[1:]))" "$@"; }
ratio() { python3 -c "import sys; print(f'{float(sys.argv[1]) / float(sys.argv[2]):.3f}')" "$1" "$2"; }

speed() {
  echo
  echo "Speed, default scene, the binaries alternating: seconds per frame after the first ($size, $spp spp, five"
  echo "runs each), and the first frame with an empty Mesa cache (32x32, llvmpipe compiles the pipelines then;"
  echo "three runs each)."
  echo
  echo "| mode | old s/frame | new s/frame | new / old | old first frame | new first frame | new / old |"
  echo "|---|---|---|---|---|---|---|"
  local m r bin
  for m in pathtrace hybrid reflections; do
    local oldFrames=() newFrames=() oldFirst=() newFirst=()
    for r in 1 2 3 4 5; do
      for bin in old new; do
        "${!bin}" render --mode "$m" --size "$size" --spp "$spp" --seed 1 --out "$out/speed.exr" \
          --stats "$out/speed.json" >/dev/null 2>&1
        local v
        v=$(json "$out/speed.json" "f\"{j['seconds_per_frame_after_first']:.4f}\"")
        if [[ $bin == old ]]; then oldFrames+=("$v"); else newFrames+=("$v"); fi
        ((r > 3)) && continue
        rm -rf "$out/mesa"
        LP_NATIVE_VECTOR_WIDTH=128 MESA_SHADER_CACHE_DIR=$out/mesa "${!bin}" render --mode "$m" --size 32x32 --spp 2 --seed 1 \
          --out "$out/speed.exr" --stats "$out/speed.json" >/dev/null 2>&1
        v=$(json "$out/speed.json" "f\"{j['frame_seconds'][0]:.3f}\"")
        if [[ $bin == old ]]; then oldFirst+=("$v"); else newFirst+=("$v"); fi
      done
    done
    local mo mn fo fn
    mo=$(median "${oldFrames[@]}") mn=$(median "${newFrames[@]}")
    fo=$(median "${oldFirst[@]}") fn=$(median "${newFirst[@]}")
    echo "| $m | ${oldFrames[*]} | ${newFrames[*]} | $(ratio "$mn" "$mo") | ${oldFirst[*]} | ${newFirst[*]} |" \
      "$(ratio "$fn" "$fo") |"
  done
}

if [[ $what != speed ]]; then images; fi
if [[ $what != images ]]; then speed; fi
