#!/usr/bin/env bash
# Sets up the machine (as root), builds, and runs the workbench on the default scene: the live window when a
# display is available, otherwise a headless render whose image path it prints. Extra arguments go to workbench.
set -euo pipefail
cd "$(dirname "$0")/.."
# The system packages: as root directly (a fresh container has no sudo), else through sudo.
if [ "$(id -u)" -eq 0 ]; then
  bash scripts/setup.sh
elif command -v sudo >/dev/null 2>&1; then
  sudo bash scripts/setup.sh
else
  echo "$0: installing the system packages needs root, and there is no sudo: run this as root" >&2
  exit 1
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target workbench
exec build/workbench "$@"
