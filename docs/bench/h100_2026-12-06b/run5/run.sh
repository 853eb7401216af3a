O=$OUT/r6; mkdir -p $O
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt
for t in test_eval_gpu test_render test_pathtracer test_debug_variants test_inspector; do
  env WB_VALIDATION=1 timeout 130 .gpu/bin/$t > $O/$t.log 2>&1; echo "$t rc $?"
done
grep -h "FAILED\|PASSED\|tests ran" $O/*.log
W=.gpu/bin/workbench
for split in 1 0; do
  WB_SPLIT_SHADOWS=$split timeout 100 $W converge assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size 256x256 --reference-spp 4096 --max-spp 256 --seconds 3600 --runs 6 --target-relmse 0.01 --config default: --out $O/sunlit_split$split > $O/sunlit_split$split.log 2>&1; echo sunlit split$split rc $?
  WB_SPLIT_SHADOWS=$split timeout 60 $W converge $WB_SHARED_DIR/reference/cornell.gltf --env-color 0,0,0 --max-bounces 64 --size 256x256 --reference $WB_SHARED_DIR/reference/cornell_cycles.exr --max-spp 128 --seconds 3600 --runs 3 --target-relmse 0.01 --config default: --out $O/cornell_split$split > $O/cornell_split$split.log 2>&1; echo cornell split$split rc $?
done
timeout 200 $W bench --only pathtracer --out $O/pathtracer.json > $O/pathtracer.log 2>&1; echo bench rc $?
rm -f $O/*/*.png $O/*/*.exr
for d in sunlit_split1 sunlit_split0 cornell_split1 cornell_split0; do echo "== $d"; grep -i "time to\|^| default" $O/$d/converge.md | cut -c1-200 | head -8; done
tail -30 $O/pathtracer.log
