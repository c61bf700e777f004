#!/usr/bin/env bash
# Installs what blastsim needs on Debian (12, bookworm) with apt-get: compiler, CMake, Ninja, Thrust
# (OpenMP backend), Catch2, toml++, CLI11, fmt, VTK (with its Python module), Gmsh, matplotlib and zlib. Only what is missing is installed.
set -euo pipefail
packages=(g++ cmake ninja-build libthrust-dev catch2 libtomlplusplus-dev libcli11-dev libfmt-dev libeigen3-dev
          libvtk9-dev libgmsh-dev python3-matplotlib python3-vtk9 zlib1g-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all Debian packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
$sudo_cmd apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
