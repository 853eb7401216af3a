#!/usr/bin/env bash
# Installs every system package the workbench needs, from scratch, idempotently. As root, or through sudo.
# Vulkan ray tracing on lavapipe needs Mesa >= 24.1; Debian 12 ships 22.3, so mesa-vulkan-drivers
# comes from bookworm-backports on the same mirror as the machine's existing Debian sources.
# slurm-wlm and munge: the single-node cluster of the sweep tests (scripts/slurm-local.sh).
set -euo pipefail

# As root directly (a fresh container has no sudo), else through sudo.
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then exec sudo bash "$0" "$@"; fi
  echo "setup.sh: installing the system packages needs root, and there is no sudo: run this as root" >&2
  exit 1
fi

stamp_dir=/var/lib/rt-workbench
stamp="$stamp_dir/setup-$(sha256sum "$0" | cut -c1-16).done"
if [ -f "$stamp" ] && [ "${SETUP_FORCE:-0}" != 1 ]; then
  echo "setup.sh: system packages already installed ($stamp); SETUP_FORCE=1 to redo"
  exit 0
fi

# Find the Debian mirror that the machine already uses (deb822 or one-line format).
mirror=""
if [ -f /etc/apt/sources.list.d/debian.sources ]; then
  mirror=$(awk '/^URIs:/ {print $2}' /etc/apt/sources.list.d/debian.sources | grep -v security | head -n1 || true)
fi
if [ -z "$mirror" ] && [ -f /etc/apt/sources.list ]; then
  mirror=$(awk '$1 == "deb" && $0 !~ /security/ {print $2; exit}' /etc/apt/sources.list || true)
fi
mirror=${mirror:-http://deb.debian.org/debian}

backports=/etc/apt/sources.list.d/bookworm-backports.list
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "deb $mirror bookworm-backports main" >"$backports"
  echo "setup.sh: added bookworm-backports from $mirror"
fi

export DEBIAN_FRONTEND=noninteractive
apt-get update -q

apt-get install -y -q --no-install-recommends \
  build-essential cmake ninja-build pkg-config git ca-certificates \
  libvulkan-dev vulkan-validationlayers vulkan-tools \
  glslang-dev glslang-tools spirv-tools spirv-cross libspirv-cross-c-shared-dev \
  libglfw3-dev libglm-dev libimgui-dev libtinygltf-dev libstb-dev libtinyexr-dev \
  nlohmann-json3-dev libxxhash-dev libcli11-dev \
  libgtest-dev libgmock-dev googletest libbenchmark-dev \
  xvfb xauth xdotool clang-format gnuplot-nox \
  slurm-wlm slurm-client munge

# Ray tracing capable lavapipe (Mesa 25.x) from backports.
apt-get install -y -q --no-install-recommends -t bookworm-backports mesa-vulkan-drivers

mkdir -p "$stamp_dir"
touch "$stamp"
echo "setup.sh: done"
