#!/usr/bin/env bash
# The test command: installs what is missing, builds the CPU backend (preset "cpu") and runs the test suite
# with CTest: the short tier (every test case not tagged [long]) by default, everything with --all.
# Usage: scripts/run-tests.sh [--all]
set -euo pipefail
cd "$(dirname "$0")/.."
tier=(-LE long)
case "${1:-}" in
  --all) tier=() ;;
  "") ;;
  *) echo "usage: scripts/run-tests.sh [--all]" >&2; exit 2 ;;
esac
scripts/install-deps.sh
cmake --preset cpu
cmake --build --preset cpu -j2
# Two test programs at a time, each on one OpenMP thread (the "cpu" test preset): two threads each would
# put four on the two cores, and OpenMP under oversubscription is several times slower.
ctest --preset cpu "${tier[@]}"
