#!/usr/bin/env bash
# Compiles and links the CUDA backend with nvcc, nothing is run (CI has no GPU), so the GPU build never rots.
# Usage: scripts/check-cuda-build.sh [--all]   (--all: the test programs too)
# Preset "cuda-check": every source through nvcc's front end to PTX for compute_90, device code unoptimised
# (-Xcicc -O0: the device optimiser took half of each unit's time) and without assembling the PTX to sm_90
# machine code (ptxas fails only on resource limits, which scripts/cuda-stack-frames.sh reports for the
# optimised kernels). Needs the CUDA toolkit at /usr/local/cuda.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x /usr/local/cuda/bin/nvcc ]; then
  echo "check-cuda-build: no nvcc at /usr/local/cuda/bin/nvcc" >&2
  exit 1
fi
cmake --preset cuda-check
# The libraries, the driver and the benchmark programs; the test programs build with nvcc in
# scripts/gpu-prebuild.sh (before every device run) or with --all here.
if [ "${1:-}" = "--all" ]; then
  cmake --build --preset cuda-check -j2
else
  cmake --build --preset cuda-check -j2 --target blastsim blastsim-bench-cip blastsim-bench-fdem blastsim-bench-coupled blastsim-bench-explosion
fi
echo "check-cuda-build: CUDA backend compiled and linked"
