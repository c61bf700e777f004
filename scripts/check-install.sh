#!/usr/bin/env bash
# Installs the CPU build (preset "cpu", built by run-tests.sh) into a temporary prefix and builds and runs
# examples/find_package_consumer against it (libcip: Sod; libfdem: fragments of a cut block): the installed CMake
# package must work for other codes.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
cmake --install build-cpu --prefix "$prefix/install" >/dev/null
cmake -S examples/find_package_consumer -B "$prefix/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix/install" >/dev/null
cmake --build "$prefix/build" >/dev/null
"$prefix/build/sod_with_blastsim"
"$prefix/build/fragments_with_blastsim"
echo "check-install: find_package(blastsim) example built and ran"
