#!/usr/bin/env bash
# Sets up the machine (as root), builds, and runs the whole test suite: a Release build with warnings as errors,
# then an AddressSanitizer + UndefinedBehaviorSanitizer build of the same tests. GPU tests run on lavapipe under
# the Khronos validation layer; any validation error fails them.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh  # the system packages (as root, or through sudo)

jobs=$(nproc)
export CTEST_OUTPUT_ON_FAILURE=1
# The machine, for reading a failure later (lavapipe's generated code depends on the CPU's vector units).
avx512=no
grep -qw avx512f /proc/cpuinfo && avx512=yes
echo "== machine: $jobs cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), AVX-512: $avx512"

echo "== Release build and tests =="
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$jobs"
(cd build && ctest -j "$jobs" --timeout 600)

if [ "${WB_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== ASan/UBSan build and tests =="
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWB_SANITIZE=ON -DWB_BENCHMARKS=OFF
  cmake --build build-asan -j "$jobs"
  # Leaks inside the Vulkan driver (llvmpipe) are not ours to fix; everything else aborts the test.
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  (cd build-asan && ctest -j "$jobs" --timeout 900)
fi
