#!/usr/bin/env bash
# Installs the Debian packages deepvox builds against, only those missing (Debian 12).
# Needs root or sudo when something is missing; prints what it installs. openimageio-tools is
# listed because Debian's OpenImageIOTargets.cmake checks that /usr/bin/iconvert exists: without
# it the CMake configure step fails (libopenimageio-dev only recommends it). clang and
# libclang-rt-dev (libFuzzer, the sanitizer runtimes) build the fuzz targets (scripts/fuzz.sh).
# libopenvdb-dev reads and writes .vdb volumes (full build; DEEPVOX_OPENVDB).
# ccache keeps compiled objects between builds and clones (CMakeLists.txt, DEEPVOX_CCACHE).
set -euo pipefail

packages=(
  cmake g++ make pkg-config git ccache
  libglm-dev libglfw3-dev libopenimageio-dev openimageio-tools python3-imath libcgal-dev libeigen3-dev
  libopenvdb-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev libcli11-dev
  libgtest-dev libbenchmark-dev
  libegl-dev libgl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0
  xvfb xauth libglx-mesa0
  python3-matplotlib
  clang libclang-rt-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "deepvox: installing missing Debian packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
