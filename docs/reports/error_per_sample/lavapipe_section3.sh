set -u
export WB_ROOT=/tmp/wbroot WB_SHADER_CACHE_DIR=/tmp/wbroot/shader_cache
wb=/work/main/.gpu/workbench
out=/tmp/eps_lavapipe
ref=/work/shared/reference
$wb converge /work/main/assets/default_scene.gltf --size 128x128 --seconds 10 --runs 3 --reference-spp 2048 \
  --config "before:--sampler sobol --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0" \
  --config "default:" --out $out/default_scene
$wb converge --hard-cases --size 48x48 --spp 64 --out $out/hard_cases
: > $out/timing_rr.txt
for r in 1 2 3; do
  for c in "owen+rr|--define WB_EMITTER_SOLID_ANGLE=0" "default|"; do
    read -r -a flags <<< "${c#*|}"
    $wb render $ref/cornell.gltf --size 256x256 --env-color 0,0,0 --max-bounces 64 --spp 16 --seed $r "${flags[@]}" \
      --out /tmp/t.exr --stats /tmp/t.json > /dev/null 2>&1
    python3 -c "import json,sys; j=json.load(open('/tmp/t.json')); print(sys.argv[1], j['seconds_per_frame_after_first'], j['device'])" "${c%%|*}" >> $out/timing_rr.txt
  done
done
echo done
