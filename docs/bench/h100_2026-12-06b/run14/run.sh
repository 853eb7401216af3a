#!/usr/bin/env bash
# Run 14: the split with its AOV variant compiled apart (WB_SPLIT_AOVS): f05c84b shaders against this tree, one binary.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
tar xJf .gpu/bundle.tar.xz -C .gpu; . .gpu/env.sh
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for v in old new; do mkdir -p /tmp/root_$v; cp -r .gpu/${v}shaders/shaders /tmp/root_$v/; ln -sfn $PWD/assets /tmp/root_$v/assets; done
mkdir -p $OUT/ab
for round in 1 2 3; do
  for v in old new loop; do
    root=/tmp/root_$v split=1; [ $v = loop ] && root=/tmp/root_new split=0
    for sz in 2048x2048:16 512x512:64; do
      WB_ROOT=$root WB_SPLIT_SHADOWS=$split .gpu/bin/workbench render --size ${sz%:*} --spp ${sz#*:} \
        --stats $OUT/ab/${v}_${sz%:*}_r$round.json --out $OUT/ab/img.png > /dev/null 2>&1 || echo "fail $v"
    done
    WB_ROOT=$root WB_SPLIT_SHADOWS=$split .gpu/bin/workbench render --size 2048x2048 --spp 16 --denoise \
      --stats $OUT/ab/${v}_denoised_r$round.json --out $OUT/ab/img.png > /dev/null 2>&1 || echo "fail $v denoised"
  done
done
rm -f $OUT/ab/img.png
bash .gpu/run1.sh | grep -v "^NVIDIA"
python3 - $OUT/ab <<'PY'
import json,glob,os,sys,collections
d=collections.defaultdict(list)
for f in sorted(glob.glob(sys.argv[1]+"/*.json")):
    j=json.load(open(f)); n=os.path.basename(f)[:-5].rsplit("_r",1)[0]
    d[n].append(j["pass_ms"]["pathtracer"])
for n,v in sorted(d.items()): print("%-18s ms/sample %s  median %.3f" % (n, " ".join("%.3f"%x for x in v), sorted(v)[1]))
PY
rm -rf $OUT/ab
