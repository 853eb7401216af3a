#!/usr/bin/env bash
# Ablations of the path tracer on the default scene at 2048x2048 (issue 29, docs/bench/roofline.md): what each
# part of its work costs per sample on the device, from `render --stats` (pass_ms: the GPU time per sample;
# rays: the rays the shaders counted). Run from the repository root on the GPU machine after unpacking the
# bundle (docs/GPU.md); W=path/to/workbench overrides the binary, OUT the output folder. Writes two variants of
# the default scene into assets/ (the leaf opaque; every material plain diffuse) and removes them after.
set -u
W=${W:-.gpu/bin/workbench}
OUT=${OUT:-out/ablation}
mkdir -p "$OUT"
python3 - <<'PY'
import json, copy
src = json.load(open('assets/default_scene.gltf'))
a = copy.deepcopy(src)
for m in a['materials']:
    if m.get('alphaMode') == 'MASK': m['alphaMode'] = 'OPAQUE'
json.dump(a, open('assets/abl_opaque.gltf', 'w'))
b = copy.deepcopy(a)
for m in b['materials']:
    if m.get('emissiveFactor'): continue
    pbr = m.setdefault('pbrMetallicRoughness', {})
    pbr['metallicFactor'] = 0.0; pbr['roughnessFactor'] = 1.0
    pbr.pop('baseColorTexture', None)
    m.pop('extensions', None)
json.dump(b, open('assets/abl_diffuse.gltf', 'w'))
PY
run() {  # name, args...
  local name=$1; shift
  $W render --size 2048x2048 --spp 16 --stats $OUT/abl_$name.json --out $OUT/abl.png "$@" > /dev/null 2>&1 || echo "$name failed"
  python3 -c "
import json;j=json.load(open('$OUT/abl_$name.json'));ms=j['pass_ms']['pathtracer'];r=j['rays']/j['spp']
print('%-14s %8.2f ms/sample  %6.3g rays/sample  %6.3g rays/s (GPU)  rays/path %.2f' % ('$name', ms, r, r/ms*1e3, j['rays']/(j['spp']*j['width']*j['height'])))"
}
for round in 1 2; do
  run default
  run no_nee --no-nee
  run bounces1 --max-bounces 1
  run bounces3 --max-bounces 3
  run leaf_opaque assets/abl_opaque.gltf
  run all_diffuse assets/abl_diffuse.gltf
  run generic --generic
done
rm -f $OUT/abl.png assets/abl_opaque.gltf assets/abl_diffuse.gltf
