#!/usr/bin/env bash
# The shadow lockstep A/B of 2026-12-05 (docs/bench/roofline.md) on the GPU machine, from the repository root after
# unpacking the bundle (docs/GPU.md): two rounds of render --stats with WB_SHADOW_LOCKSTEP=0 and 1 on four scenes.
OUT=${OUT:-out/lockstep}
mkdir -p "$OUT"
W=${W:-.gpu/bin/workbench}
one() {  # name define args...
  local name=$1 d=$2; shift 2
  $W render --spp 16 --define WB_SHADOW_LOCKSTEP=$d --stats $OUT/ls_${name}_$d.json --out $OUT/ls.png "$@" > /dev/null 2>&1 || echo "$name $d failed"
  python3 -c "
import json;j=json.load(open('$OUT/ls_${name}_$d.json'));ms=j['pass_ms']['pathtracer']
print('%-12s lockstep=%s %8.3f ms/sample  %.4g rays/s  mean %.5f' % ('$name', '$d', ms, j['rays']/j['spp']/ms*1e3, j['mean_rgb'][0]))"
}
for round in 1 2; do
  for d in 0 1; do
    one default2048 $d --size 2048x2048
    one sunlit2048 $d --size 2048x2048 assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5
    one default512 $d --size 512x512
    one helmet512 $d --size 512x512 .gpu/shared/assets/gltf/DamagedHelmet/DamagedHelmet.gltf
  done
done
rm -f $OUT/ls.png
