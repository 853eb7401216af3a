O=$OUT/r5; mkdir -p $O
for t in test_eval_gpu test_render test_pathtracer test_debug_variants; do
  env WB_VALIDATION=1 timeout 130 .gpu/bin/$t > $O/$t.log 2>&1; echo "$t rc $?"
done
grep -h "FAILED\|PASSED\|tests ran\|red wall\|cost variant" $O/*.log
W=.gpu/bin/workbench
timeout 100 $W converge assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size 256x256 --reference-spp 4096 --max-spp 256 --seconds 3600 --runs 8 --target-relmse 0.01 --config default: --config "no-guiding:--define WB_REFLECTOR_GUIDING=0" --out $O/sunlit > $O/sunlit.log 2>&1; echo sunlit rc $?
timeout 60 $W converge $WB_SHARED_DIR/reference/cornell.gltf --env-color 0,0,0 --max-bounces 64 --size 256x256 --reference $WB_SHARED_DIR/reference/cornell_cycles.exr --max-spp 128 --seconds 3600 --runs 3 --target-relmse 0.01 --config default: --out $O/cornell > $O/cornell.log 2>&1; echo cornell rc $?
rm -f $O/*/*.png
for d in sunlit cornell; do grep "^| " $O/$d/converge.md | cut -c1-330; done
