#!/usr/bin/env bash
# The test command: installs what is missing, builds the CPU backend (preset "cpu") and runs the whole
# test suite with CTest. Usage: scripts/run-tests.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset cpu
cmake --build --preset cpu -j2
# Two test programs at a time, each on one OpenMP thread (the "cpu" test preset): two threads each would
# put four on the two cores, and OpenMP under oversubscription is several times slower.
ctest --preset cpu
