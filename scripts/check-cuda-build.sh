#!/usr/bin/env bash
# Compiles and links the CUDA backend with nvcc (preset "cuda"; no GPU needed, nothing is run), so the
# GPU build never rots. Needs the CUDA toolkit at /usr/local/cuda.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x /usr/local/cuda/bin/nvcc ]; then
  echo "check-cuda-build: no nvcc at /usr/local/cuda/bin/nvcc" >&2
  exit 1
fi
cmake --preset cuda
cmake --build --preset cuda -j2
echo "check-cuda-build: CUDA backend compiled and linked"
