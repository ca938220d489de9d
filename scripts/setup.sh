#!/usr/bin/env bash
# Installs every Debian package Lantern needs (idempotent; quick when nothing is missing).
# Mesa 25 lavapipe comes from bookworm-backports: stock bookworm Mesa 22 has no ray query,
# no descriptor indexing and a 2 GiB heap (shared/PLATFORM.md).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libvulkan-dev vulkan-validationlayers vulkan-tools spirv-tools glslang-tools glslang-dev
  libglfw3-dev libglm-dev libimgui-dev
  libopenimageio-dev openimageio-tools
  libopenvdb-dev libboost-dev libboost-iostreams-dev libtbb-dev
  libnanovdb-dev  # PNanoVDB.h: volume_lookup_bench (the bricks against NanoVDB)
  libtinygltf-dev libstb-dev nlohmann-json3-dev libcli11-dev libfmt-dev spirv-headers
  libgtest-dev libgmock-dev libbenchmark-dev
  libembree-dev  # Intel Embree 3: the host visibility backend (lighting/visibility/host_visibility.h)
  xvfb xauth ffmpeg fonts-dejavu-core
  clang-14 libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer
)
backports_packages=(mesa-vulkan-drivers)
min_mesa="25"

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
need_mesa=1
if [ -n "$mesa_version" ] && dpkg --compare-versions "$mesa_version" ge "$min_mesa"; then need_mesa=0; fi

if [ ${#missing[@]} -eq 0 ] && [ $need_mesa -eq 0 ]; then
  echo "setup: all packages present (mesa-vulkan-drivers $mesa_version)"
  exit 0
fi

backports=/etc/apt/sources.list.d/bookworm-backports.sources
if [ ! -f "$backports" ] && ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "setup: adding Debian bookworm-backports"
  as_root tee "$backports" >/dev/null <<'SRC'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
fi

export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]} ${backports_packages[*]}"
as_root apt-get update -qq
as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
if [ $need_mesa -eq 1 ]; then
  as_root apt-get install -y -qq --no-install-recommends -t bookworm-backports "${backports_packages[@]}" >/dev/null
fi
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers)
dpkg --compare-versions "$mesa_version" ge "$min_mesa" ||
  { echo "setup: mesa-vulkan-drivers $mesa_version is older than $min_mesa" >&2; exit 1; }
echo "setup: done (mesa-vulkan-drivers $mesa_version)"
