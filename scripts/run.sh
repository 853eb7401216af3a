#!/usr/bin/env bash
# Sets up the machine (as root), builds, and runs the workbench on the default scene: the live window when a
# display is available, otherwise a headless render whose image path it prints. Extra arguments go to workbench.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh  # the system packages (as root, or through sudo)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target workbench
exec build/workbench "$@"
