#!/usr/bin/env bash
# Run 11: where guiding's time goes on the sunlit scene (fraction ~0: the code without its rays), and bench denoise.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
tar xJf .gpu/bundle.tar.xz -C .gpu; . .gpu/env.sh
W=.gpu/bin/workbench
mkdir -p $OUT/g
for round in 1 2 3; do
  for cfg in "none:-D WB_REFLECTOR_GUIDING=0" "c0:-D WB_REFLECTOR_FRACTION=0.0001" "c015:-D WB_REFLECTOR_FRACTION=0.15" "default:" "perpixel:-D WB_REFLECTOR_COHERENT=0"; do
    name=${cfg%%:*}; defs=${cfg#*:}; args=()
    [ -n "$defs" ] && args=(--define "${defs#-D }")
    for sz in 256x256:512 2048x2048:16; do
      $W render assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size ${sz%:*} --spp ${sz#*:} "${args[@]}" \
        --stats $OUT/g/${name}_${sz%:*}_r$round.json --out $OUT/g/img.png > /dev/null 2>&1 || echo "fail $name"
    done
  done
done
rm -f $OUT/g/img.png
python3 - $OUT/g <<'PY'
import json,glob,os,sys,collections
d=collections.defaultdict(list)
for f in sorted(glob.glob(sys.argv[1]+"/*.json")):
    j=json.load(open(f)); n=os.path.basename(f)[:-5].rsplit("_r",1)[0]
    d[n].append((j["pass_ms"]["pathtracer"], j["rays"]/j["spp"], j["shadow_rays"]/j["spp"]))
for n,v in sorted(d.items()):
    print("%-20s ms/sample %s  rays/sample %.4g shadow %.4g" % (n, " ".join("%.3f"%x[0] for x in v), v[0][1], v[0][2]))
PY
$W bench --only denoise --out $OUT/denoise.json > $OUT/denoise.log 2>&1; echo "bench rc=$?"
python3 -c "
import json;d=json.load(open('$OUT/denoise.json'))['denoise']
for c in d['cost']: print(c['size'],round(c['denoise_ms'],3),round(c['sample_ms'],3),round(c['denoise_share_of_sample'],4),{k:round(v,3) for k,v in c['denoise_pass_ms'].items()})
print('cornell',d['denoised_vs_raw_time_to_relmse_0.01'])"
