O=$OUT/r8; mkdir -p $O
for t in test_render test_pathtracer test_debug_variants test_inspector; do
  env WB_VALIDATION=1 timeout 130 .gpu/bin/$t > $O/$t.log 2>&1; echo "$t rc $?"
done
grep -h "FAILED\|PASSED" $O/*.log
W=.gpu/bin/workbench
for s in 0 1; do WB_SPLIT_SHADOWS=$s $W render --size 512x512 --spp 64 --stats $O/s$s.json --out $O/s$s.exr > /dev/null 2>&1; done
WB_SPLIT_SHADOWS=1 $W render --size 512x512 --spp 64 --reference $O/s0.exr --stats $O/cmp.json --out $O/x.png > /dev/null 2>&1
python3 -c "
import json
for f in ['s0','s1','cmp']:
    j=json.load(open('$O/'+f+'.json')); print(f, j['split_shadows'], j['pass_ms'], j['rays'], j.get('error_vs_reference',{}).get('rel_mse'))"
rm -f $O/*.exr $O/*.png
