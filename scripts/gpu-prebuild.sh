#!/usr/bin/env bash
# Builds the CUDA backend for the H200 (sm_90a) on this machine and packs what scripts/gpu-bench.sh runs (the
# executables and the CTest files, no object files) into .gpu-bin/build-cuda.tar.xz, so a device call spends its
# minutes running rather than compiling. Carry .gpu-bin and .deps in the call; gpu-bench.sh unpacks the archive,
# checks that the binaries start there and builds on the GPU machine instead when they do not.
# Usage: scripts/gpu-prebuild.sh            (about 30 min on 2 cores; needs nvcc at /usr/local/cuda)
set -euo pipefail
cd "$(dirname "$0")/.."
# Without Gmsh: the GPU machine has no libgmsh (meshes there come from the ring mesher or .msh files).
cmake --preset cuda -DCMAKE_CUDA_ARCHITECTURES=90a -DBLASTSIM_ENABLE_GMSH=OFF > /dev/null
cmake --build --preset cuda -j"${JOBS:-2}"
mkdir -p .gpu-bin
# Executables, the CTest scripts (with the discovered test lists) and the cache that names the source tree.
(find build-cuda -type f \( -perm -u+x -path '*/apps/*' -o -perm -u+x -path '*/tests/*' \) ! -path '*/CMakeFiles/*' \
   ! -name '*.o' ! -name '*.a'
 find build-cuda -name 'CTestTestfile.cmake' -o -name '*_tests-*.cmake' -o -name '*_include-*.cmake' \
   -o -name '*_long_labels.cmake'
 echo build-cuda/CMakeCache.txt) | sort -u > .gpu-bin/files.txt
# Staged copies with the symbol tables stripped (the carried tree must stay under the device tool's 64 MiB).
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
tar -cf - -T .gpu-bin/files.txt | tar -xf - -C "$stage"
find "$stage" -type f -perm -u+x -exec strip --strip-unneeded {} +
tar -cJf .gpu-bin/build-cuda.tar.xz -C "$stage" build-cuda
rm -f .gpu-bin/build-cuda.tar.gz
git rev-parse HEAD > .gpu-bin/commit.txt
echo "gpu-prebuild: $(wc -l < .gpu-bin/files.txt) files, $(du -h .gpu-bin/build-cuda.tar.xz | cut -f1) in .gpu-bin/build-cuda.tar.xz" \
     "(tree $(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo ', with uncommitted changes'))"
