O=$OUT/r3; mkdir -p $O; W=.gpu/bin/workbench
env WB_VALIDATION=1 timeout 200 .gpu/bin/test_debug_variants > $O/debug_variants.log 2>&1; echo debug_variants rc $?
env WB_VALIDATION=1 timeout 240 .gpu/bin/test_inspector > $O/inspector.log 2>&1; echo inspector rc $?
G1="guiding:--define WB_REFLECTOR_GUIDING=1"; G2="guiding-own:--define WB_REFLECTOR_GUIDING=1 --define WB_REFLECTOR_COHERENT=0"
timeout 150 $W converge assets/default_scene.gltf --size 256x256 --reference-spp 16384 --max-spp 1024 --seconds 3600 --runs 12 --config default: --config "$G1" --out $O/default_guiding > $O/default_guiding.log 2>&1; echo default rc $?
timeout 120 $W converge assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size 256x256 --reference-spp 4096 --max-spp 256 --seconds 3600 --runs 8 --target-relmse 0.01 --config default: --config "$G1" --config "$G2" --out $O/sunlit > $O/sunlit.log 2>&1; echo sunlit rc $?
rm -f $O/*/*.png
grep -h "red wall\|cost variant\|PASSED\|FAILED" $O/debug_variants.log $O/inspector.log
for d in default_guiding sunlit; do grep "^| " $O/$d/converge.md | cut -c1-400; done
