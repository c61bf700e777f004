#!/usr/bin/env bash
# Unpacks the header-only (and small static) Debian packages the build needs into .deps/ (git-ignored), for
# a GPU machine that has nvcc and CMake but no package registry: copy .deps/ there with the checkout and
# configure with -DCMAKE_PREFIX_PATH=$PWD/.deps/usr (the "cuda" preset does). Extra package names may follow.
# Usage: scripts/device-deps.sh [PACKAGE...]
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(libeigen3-dev libfmt-dev libfmt9 catch2 libtomlplusplus-dev libtomlplusplus3 libcli11-dev zlib1g-dev "$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if ! (cd "$work" && apt-get download "${packages[@]}" >/dev/null 2>&1); then
  apt-get update -qq
  (cd "$work" && apt-get download "${packages[@]}" >/dev/null)
fi
rm -rf .deps
mkdir -p .deps
for deb in "$work"/*.deb; do dpkg -x "$deb" .deps; done
rm -rf .deps/usr/share/doc .deps/usr/share/man
echo "device-deps: $(du -sh .deps | cut -f1) in .deps/ (configure with -DCMAKE_PREFIX_PATH=\$PWD/.deps/usr)"
