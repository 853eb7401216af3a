#!/usr/bin/env bash
# Issue 20: does spherical-triangle light sampling pay on its own? "owen+rr" = the default without it.
set -u
ref=$WB_SHARED_DIR/reference
wb=.gpu/workbench
sa0="--define WB_EMITTER_SOLID_ANGLE=0"
configs=(
  "owen|--sampler owen --rr-exponent 1 --rr-start 2 $sa0"
  "owen+solid-angle|--sampler owen --rr-exponent 1 --rr-start 2"
  "owen+rr|$sa0"
  "default|"
)
args=()
for c in "${configs[@]}"; do args+=(--config "${c%%|*}:${c#*|}"); done
$wb converge "$ref/cornell.gltf" --size 256x256 --env-color 0,0,0 --max-bounces 64 --reference "$ref/cornell_cycles.exr" \
  --seconds 3600 --max-spp 128 --runs 3 --target-relmse 0.01 "${args[@]}" --out /tmp/x/cornell_rr
: > /tmp/x/timing.txt
for r in 1 2 3 4 5 6 7; do
  for c in "${configs[@]}"; do
    read -r -a flags <<< "${c#*|}"
    $wb render "$ref/cornell.gltf" --size 1024x1024 --env-color 0,0,0 --max-bounces 64 --spp 16 --seed $r "${flags[@]}" \
      --out /tmp/t.exr --stats /tmp/t.json > /dev/null 2>&1
    python3 -c "import json,sys; j=json.load(open('/tmp/t.json')); print(sys.argv[1], j['seconds_per_frame_after_first'], j['rays_per_second'], j['paths_per_second'])" "${c%%|*}" >> /tmp/x/timing.txt
  done
done
cat /tmp/x/timing.txt; sed -n '/^| config/,/^$/p' /tmp/x/cornell_rr/converge.md
