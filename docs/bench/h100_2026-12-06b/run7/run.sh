O=$OUT/r7; mkdir -p $O
W=.gpu/bin/workbench
timeout 250 $W converge assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size 256x256 --reference-spp 8192 --max-spp 512 --seconds 3600 --runs 12 --target-relmse 0.01 --config guided: --config "unguided:--define WB_REFLECTOR_GUIDING=0" --out $O/sunlit > $O/sunlit.log 2>&1; echo sunlit rc $?
timeout 250 $W converge assets/default_scene.gltf --size 256x256 --reference-spp 8192 --max-spp 512 --seconds 3600 --runs 8 --config guided: --config "unguided:--define WB_REFLECTOR_GUIDING=0" --out $O/default > $O/default.log 2>&1; echo default rc $?
rm -f $O/*/*.png $O/*/*.exr
for d in sunlit default; do echo "== $d"; grep "^| guided\|^| unguided\|^| config" $O/$d/converge.md | cut -c1-250; done
