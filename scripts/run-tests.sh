#!/usr/bin/env bash
# The test command: installs what is missing, builds the CPU backend (preset "cpu") and runs the whole
# test suite with CTest. Usage: scripts/run-tests.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset cpu
cmake --build --preset cpu -j2
ctest --preset cpu
