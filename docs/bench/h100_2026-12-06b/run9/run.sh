#!/usr/bin/env bash
# Run 9 (2026-12-06 session 2): the GPU tests at bf53c46, then the split step (with the denoised renders).
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
tar xJf .gpu/bundle.tar.xz -C .gpu; . .gpu/env.sh
mkdir -p /work/main/build && ln -sf $PWD/.gpu/bin/workbench /work/main/build/workbench
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
export WB_VALIDATION=1
for t in test_render test_pathtracer test_denoiser test_inspector test_debug_variants test_eval_gpu; do
  f='*'; [ $t = test_inspector ] && f='-HybridInspector.*'
  s=$(date +%s); timeout 200 .gpu/bin/$t --gtest_filter="$f" > $OUT/$t.log 2>&1; rc=$?
  echo "$t rc=$rc $(( $(date +%s) - s ))s $(grep -E '^\[  (PASSED|FAILED) ' $OUT/$t.log | tr '\n' ' ')"
done
grep -h "FAILED  \]\|VUID" $OUT/*.log | sort | uniq | head -20
