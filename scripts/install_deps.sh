#!/usr/bin/env bash
# Installs the Debian 12 packages sewer3d needs to build and test. Idempotent.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libopencv-dev libopencv-contrib-dev libceres-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev libspectra-dev zlib1g-dev
  libtinyobjloader-dev
  clang-format clang-tidy python3
  clang libclang-rt-14-dev
  chromium
)
# The report's 3D viewer fetches three.js with npm at configure time; its browser test runs
# Chromium through Node (any Node from 18 on; a newer one already installed is kept).
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install_deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
