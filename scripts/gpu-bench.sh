#!/usr/bin/env bash
# One device call on the GPU machine, inside a deadline: the CUDA binaries (prebuilt here by
# scripts/gpu-prebuild.sh, or built there when they do not start), the default single-hole blast on the GPU
# (every coupling: crack gas, face forces, monitors), the test suite's short tier on the GPU (backend agreement
# and fragment labels included) beside compute-sanitizer memcheck, the benchmarks (gas, rock, the coupled step
# phase by phase, fused and separate), Nsight Compute on one coupled step, and the paper-scale case for the
# time that is left. Logs under $OUT (at most 8 files: the device tool returns no more), a short table last.
# Usage (device tool, carrying .gpu-bin and .deps):  bash scripts/gpu-bench.sh [SECONDS [paper]]   (default 560)
#   paper: a short second call: the default example with --profile (every kernel's time, crack gas included) and
#   the paper-scale case, nothing else.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
out=${OUT:-$PWD/out}
mkdir -p "$out"
summary=$out/summary.txt
: > "$summary"
note() { echo "$*" | tee -a "$summary"; }
mode=${2:-all}
case "$mode" in all|paper) ;; *) echo "gpu-bench: mode '$mode': use all (default) or paper" >&2; exit 2 ;; esac
start=$(date +%s)
deadline=$((start + ${1:-560}))
left() { echo $((deadline - $(date +%s))); }
# cap SECONDS: at most SECONDS, and never past the deadline less 10 s for the summary
cap() { local l=$(($(left) - 10)); [ "$l" -lt "$1" ] && echo $((l > 1 ? l : 1)) || echo "$1"; }
jobs=$(nproc)
bin=build-cuda/apps/blastsim/blastsim

nvidia-smi --query-gpu=name,memory.total,clocks.max.sm,clocks.max.mem,driver_version --format=csv,noheader | tee -a "$summary"
note "date: $(date -u +%Y-%m-%dT%H:%MZ)  tree: $(cat .gpu-bin/commit.txt 2>/dev/null || git rev-parse HEAD 2>/dev/null || echo unknown)  nproc $jobs"

# 1. Binaries: the prebuilt ones if they start here, else a build on this machine.
if [ -f .gpu-bin/build-cuda.tar.xz ] && [ ! -x "$bin" ]; then tar -xJf .gpu-bin/build-cuda.tar.xz; fi
# The CTest files and the tests name the source tree by the path it had where they were built.
src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' build-cuda/CMakeCache.txt 2>/dev/null)
if [ -n "$src" ] && [ "$src" != "$PWD" ] && [ ! -e "$src" ]; then mkdir -p "$(dirname "$src")" && ln -s "$PWD" "$src"; fi
# The prebuilt binaries load the CUDA runtime of the machine's toolkit (found through its usual folders).
export LD_LIBRARY_PATH=/usr/local/cuda/lib64:/usr/local/cuda/targets/x86_64-linux/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
if "$bin" --help > /dev/null 2>&1; then
  note "binaries: prebuilt (sm_90a), start here"
else
  note "binaries: prebuilt ones absent or do not start ($("$bin" --help 2>&1 | head -1)); building here"
  rm -rf build-cuda
  t0=$(date +%s)
  cmake --preset cuda -DCMAKE_CUDA_ARCHITECTURES=90a > "$out/build.log" 2>&1 &&
    timeout "$(cap 330)" cmake --build --preset cuda -j"$jobs" >> "$out/build.log" 2>&1
  note "build: rc=$? in $(( $(date +%s) - t0 )) s"
  "$bin" --help > /dev/null 2>&1 || { tail -30 "$out/build.log"; exit 1; }
fi

if [ "$mode" = paper ]; then
  t0=$(date +%s)
  timeout "$(cap 60)" "$bin" --profile examples/single_hole/single_hole.toml rock.mesh.mesher=rings output.vtk=false \
    output.directory=single_hole_gpu > "$out/single_hole_gpu_profile.log" 2>&1
  note "single-hole with --profile on the GPU: rc=$? in $(( $(date +%s) - t0 )) s"
fi

# Steps 2-5 in the full call only (mode all).
if [ "$mode" = all ]; then
# 2. The default single-hole example on the GPU, to its end or the cap (rings mesh: no Gmsh there).
t0=$(date +%s)
timeout "$(cap 100)" "$bin" examples/single_hole/single_hole.toml rock.mesh.mesher=rings output.vtk=false \
  output.directory=single_hole_gpu > "$out/single_hole_gpu.log" 2>&1
rc=$?
note "single-hole (default, rings mesh) on the GPU: rc=$rc in $(( $(date +%s) - t0 )) s; $(grep -E '^coupled: [0-9]+ steps' "$out/single_hole_gpu.log" | tail -1)"
grep -E 'free face|outer surface|first crack' single_hole_gpu/summary.txt 2>/dev/null | head -6 | tee -a "$summary"
tar --exclude='*.bin' -czf "$out/single_hole_gpu.tar.gz" single_hole_gpu 2>/dev/null

# 3. The short tier on the GPU, and memcheck beside it (neither is a timing).
t0=$(date +%s)
( ctest --test-dir build-cuda -LE long -j6 --timeout 200 --stop-time "$(date -d @$((deadline - 200)) +%H:%M:%S)" \
    > "$out/ctest.log" 2>&1; echo "ctest_rc=$?" >> "$out/ctest.log" ) &
ctest_pid=$!
mc() { timeout "$(cap 80)" compute-sanitizer --tool memcheck --error-exitcode 9 "$@" >> "$out/memcheck.log" 2>&1; echo $?; }
: > "$out/memcheck.log"
r1=$(mc "$bin" -q examples/single_hole/single_hole.toml rock.mesh.mesher=rings domain.nx=96 domain.ny=96 \
       rock.mesh.element_size=0.05 time.end=6e-5 output.vtk=false output.directory=/tmp/mc_single_hole)
note "memcheck, single hole 96^2 to 60 us (crack gas, face forces, monitors): rc=$r1 $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"
# (without Gmsh on the GPU machine the charge tests, K1-K6, and C4 are not built: their kernels are memchecked
# only when that machine has a Gmsh)
r2=$(mc build-cuda/tests/ibm/test_ibm "[C1],[C3],[I2],[I6],[I8],[K1],[K3],[C4]")
note "memcheck, test_ibm [C1],[C3],[I2],[I6],[I8] and, where built, [K1],[K3],[C4] (crack channels, shock on a block, ANFO products in rock, face forces, charges): rc=$r2 $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"
r3=$(mc build-cuda/tests/fdem/test_fdem "[determinism],[F7]")
note "memcheck, test_fdem [determinism],[F7] (fracture, contact): rc=$r3 $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"
wait $ctest_pid
note "ctest -LE long on the GPU in $(( $(date +%s) - t0 )) s: $(grep -E 'tests passed|tests failed' "$out/ctest.log") $(grep ctest_rc "$out/ctest.log")"
grep -E '\*\*\*Failed|\*\*\*Timeout|Not Run|Exception' "$out/ctest.log" | head -10 | tee -a "$summary"
grep -E 'backend agreement|fragment' "$out/ctest.log" | head -4 | tee -a "$summary"

# 4. Benchmarks (alone on the GPU): gas step, rock step, the coupled step phase by phase.
b=build-cuda/apps/bench
: > "$out/bench.log"
timeout "$(cap 40)" $b/blastsim-bench-cip --sizes=2500,5001 --steps=20 >> "$out/bench.log" 2>&1; note "bench_cip rc=$?"
timeout "$(cap 40)" $b/blastsim-bench-fdem --sizes=187,1024 --steps=50 >> "$out/bench.log" 2>&1; note "bench_fdem rc=$?"
for fusion in --fused --separate; do
  timeout "$(cap 60)" $b/blastsim-bench-coupled --cases=2501:0.019,5001:0.0095 --steps=20 --gas-load=faces --kernels \
    "$fusion" >> "$out/bench.log" 2>&1
  note "bench_coupled $fusion rc=$?"
done
grep -E 'copy bandwidth|^case|^step:|ms/step|updates|floor' "$out/bench.log" | grep -v '^    ' | head -60 >> "$summary"

# 5. Nsight Compute: every kernel of two or three whole coupled steps at quarter size (after the warm-up).
if command -v ncu > /dev/null && [ "$(left)" -gt 120 ]; then
  timeout "$(cap 60)" ncu --clock-control none --csv \
    --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,launch__registers_per_thread,sm__warps_active.avg.pct_of_peak_sustained_active,launch__grid_size \
    --launch-skip 400 --launch-count 150 $b/blastsim-bench-coupled --cases=2501:0.019 --steps=2 --warmup=8 --fused \
    --gas-load=faces > "$out/ncu_coupled.csv" 2>&1
  note "ncu rc=$? (per-kernel table in ncu_coupled.csv)"
fi

fi  # mode all

# 6. The paper-scale case (5001^2 cells, 9.5 mm triangles, dt 20 ns) for the time that is left.
if [ "$(left)" -gt 60 ]; then
  t0=$(date +%s)
  timeout "$(cap 400)" "$bin" examples/single_hole/single_hole_paper.toml rock.mesh.mesher=rings output.vtk=false \
    output.checkpoint=false output.directory=paper_gpu > "$out/paper_gpu.log" 2>&1
  note "paper scale (crack gas, face forces): rc=$? after $(( $(date +%s) - t0 )) s; last progress: $(grep -E '^step' "$out/paper_gpu.log" | tail -1)"
  grep -E '^step' "$out/paper_gpu.log" | head -2 | tee -a "$summary"
fi
echo "==== summary ($(( $(date +%s) - start )) s)"
cat "$summary"
