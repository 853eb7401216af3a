#!/usr/bin/env bash
# Run 10: reflector guiding's fraction on the H100 (item 4): sunlit 256x256 and default 256x256, 8 runs each.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
tar xJf .gpu/bundle.tar.xz -C .gpu; . .gpu/env.sh
W=.gpu/bin/workbench
fr=(--config default: --config "fraction-0.15:--define WB_REFLECTOR_FRACTION=0.15"
    --config "fraction-0.2:--define WB_REFLECTOR_FRACTION=0.2" --config "no-guiding:--define WB_REFLECTOR_GUIDING=0")
s=$(date +%s)
$W converge assets/sunlit_spheres.gltf --env-color 0.2,0.3,0.5 --size 256x256 --reference-spp 4096 --max-spp 512 \
  --seconds 3600 --runs 8 --target-relmse 0.01 "${fr[@]}" --out $OUT/sunlit > $OUT/sunlit.log 2>&1; echo "sunlit rc=$? $(( $(date +%s) - s ))s"
s=$(date +%s)
$W converge assets/default_scene.gltf --size 256x256 --reference-spp 16384 --max-spp 1024 \
  --seconds 3600 --runs 8 "${fr[@]}" --out $OUT/default > $OUT/default.log 2>&1; echo "default rc=$? $(( $(date +%s) - s ))s"
rm -f $OUT/*/*.exr $OUT/*/*.png
for d in sunlit default; do grep -E "^\| (config|default|fraction|no-guiding)" $OUT/$d/converge.md | head -8; done
