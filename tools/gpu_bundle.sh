#!/usr/bin/env bash
# Packs what a run on a borrowed GPU machine needs into .gpu/bundle.tar.xz (docs/GPU.md): the stripped
# workbench and the named test executables from build/, the shared libraries they load that the machine may
# lack, the Khronos validation layer, and ../shared (models, references). Unpack it there with
# `tar xJf .gpu/bundle.tar.xz -C .gpu` and source .gpu/env.sh.
#
#   bash tools/gpu_bundle.sh [TEST_EXECUTABLE...]      e.g. bash tools/gpu_bundle.sh test_live_gpu test_render
set -euo pipefail
cd "$(dirname "$0")/.."
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib" "$stage/layer" "$stage/bin" .gpu
for exe in workbench "$@"; do
  strip -o "$stage/bin/$exe" "build/$exe"
done
for l in libtinyexr.so.1d libstb.so.0 libtinygltf.so.2d libxxhash.so.0 libglfw.so.3 libX11.so.6 libxcb.so.1 \
         libXau.so.6 libXdmcp.so.6 libbsd.so.0 libmd.so.0; do
  cp -L "/lib/x86_64-linux-gnu/$l" "$stage/lib/"
done
cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$stage/layer/"
cp /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json "$stage/layer/"
cp -r ../shared "$stage/shared"
cat > "$stage/env.sh" <<'EOF'
# Sourced from the repository root on the GPU machine after unpacking the bundle into .gpu/.
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
# The validation layer library sits beside its manifest, which names it without a path: the loader dlopens it
# through LD_LIBRARY_PATH.
export LD_LIBRARY_PATH=$PWD/.gpu/lib:$PWD/.gpu/layer VK_LAYER_PATH=$PWD/.gpu/layer WB_SHARED_DIR=$PWD/.gpu/shared
# The binaries find shaders/ and assets/ from their own location: they sit in the repository root's .gpu/bin,
# so WB_ROOT names the root.
export WB_ROOT=$PWD
EOF
tar cJf .gpu/bundle.tar.xz -C "$stage" .
ls -la .gpu/bundle.tar.xz
