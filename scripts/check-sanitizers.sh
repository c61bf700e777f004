#!/usr/bin/env bash
# CI: the short test tier under AddressSanitizer + UndefinedBehaviorSanitizer (preset "sanitize": -O1, no VTK;
# the libraries and the driver instrumented, the test programs' own code not (BLASTSIM_SANITIZE, CMakeLists.txt);
# UBSan halts on the first report; scripts/ubsan.supp lists the third-party reports it ignores), less the cases
# tagged [heavy]: many steps of kernels that shorter cases also run (docs/architecture.md "Tests"). Builds only
# what the tests run.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j2 --target blastsim test_cip test_fdem test_ibm test_app
# The rock-mass fuzz draws 24 inputs in the tests stage, uninstrumented; 8 of them here (BLASTSIM_FUZZ_RUNS).
BLASTSIM_FUZZ_RUNS=8 ctest --preset sanitize -LE "long|heavy"
echo "check-sanitizers: the short tier (less [heavy]) clean under ASan + UBSan"
