#!/usr/bin/env bash
# Issue 20, streamlined solid-angle sampling: the H200 run of 2026-12-03 (one `device` call, 129 s), from the
# repository root with .gl/ (Debian's loader and glvnd .debs) and .gpu/i20/ carried: .gpu/i20/workbench (build of
# branch i20 at d2cdf31, stripped) and lib/ as docs/GPU.md lists, shared/reference from ../shared, and root/ =
# `git archive d2cdf31 shaders assets` plus bench/error_per_sample.sh of 7cacc71 (WB_ROOT). At d2cdf31 the
# default ratio was still 1.0: the "default" rows here are ratio 1, the chosen default (1.5) is "ratio1.5".
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
G=$PWD/.gpu/i20
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$G/lib \
  WB_SHARED_DIR=$G/shared WB_ROOT=$G/root WB_SHADER_CACHE_DIR=/tmp/sc
cd $G/root
ref=$G/shared/reference
bash bench/error_per_sample.sh -b $G/workbench -o /tmp/eps -t 1024x1024 -r 7 -s 5 \
  -c 'ratio1.5|--define WB_EMITTER_SOLID_ANGLE_RATIO=1.5' -c 'ratio2|--define WB_EMITTER_SOLID_ANGLE_RATIO=2.0'
# 8 seeds of the configurations that matter here (cornell_8seeds.*).
$G/workbench converge $ref/cornell.gltf --size 256x256 --env-color 0,0,0 --max-bounces 64 \
  --reference $ref/cornell_cycles.exr --seconds 3600 --max-spp 128 --runs 8 --target-relmse 0.01 \
  --config 'owen+rr:--define WB_EMITTER_SOLID_ANGLE=0' --config 'previous:--define WB_EMITTER_SOLID_ANGLE=1' \
  --config 'default:' --config 'ratio1.5:--define WB_EMITTER_SOLID_ANGLE_RATIO=1.5' --out /tmp/eps8
