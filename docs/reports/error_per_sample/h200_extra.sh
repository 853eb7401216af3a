#!/usr/bin/env bash
# Extra H200 measurements for docs/reports/error_per_sample.md (issue 20).
set -u
ref=$WB_SHARED_DIR/reference
o=$1
wb=.gpu/workbench
# A. Cornell, per seed: 8 independent seeds per configuration, one run each, up to 128 spp.
args=()
for k in 1 2 3 4 5 6 7 8; do
  args+=(--config "default_s$k:--seed $((k * 100000))")
  args+=(--config "before_s$k:--seed $((k * 100000)) --sampler sobol --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0")
done
$wb converge "$ref/cornell.gltf" --size 256x256 --env-color 0,0,0 --max-bounces 64 --reference "$ref/cornell_cycles.exr" \
  --seconds 3600 --max-spp 128 --runs 1 --target-relmse 0.01 "${args[@]}" --out /tmp/x/cornell_seeds
# B. Default scene, 128x128, 5 s x 3 runs, against a 131072-spp reference (the 2048-spp one is noisier than the runs).
timeout 420 $wb converge --size 128x128 --seconds 5 --runs 3 --reference-spp 131072 \
  --config "before:--sampler sobol --rr-exponent 1 --rr-start 2 --define WB_EMITTER_SOLID_ANGLE=0" \
  --config "default:" --out /tmp/x/default_scene_deepref
echo "rc_B=$?"
