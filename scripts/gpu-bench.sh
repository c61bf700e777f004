#!/usr/bin/env bash
# One device call on the GPU machine: build the CUDA backend, run the test suite on the GPU, run
# compute-sanitizer (memcheck) on a small case, then the benchmarks; logs under $OUT (at most 8 files: the
# device tool returns no more), a short table last.
# Usage (device tool, carrying .deps made by scripts/device-deps.sh):  bash scripts/gpu-bench.sh [quick]
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-$PWD/out}
mkdir -p "$out"
summary=$out/summary.txt
: > "$summary"
note() { echo "$*" | tee -a "$summary"; }
jobs=$(nproc)

nvidia-smi --query-gpu=name,memory.total,clocks.max.sm,clocks.max.mem --format=csv | tee -a "$summary"
note "date: $(date -u +%Y-%m-%dT%H:%MZ)  commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"

t0=$(date +%s)
cmake --preset cuda -DCMAKE_CUDA_COMPILER="$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)" -DCMAKE_CUDA_ARCHITECTURES=90a \
  > /tmp/configure.log 2>&1 && cmake --build --preset cuda -j"$jobs" > "$out/build.log" 2>&1
build_rc=$?
note "build: rc=$build_rc in $(( $(date +%s) - t0 )) s"
if [ $build_rc -ne 0 ]; then cat /tmp/configure.log; tail -40 "$out/build.log"; exit 1; fi

t0=$(date +%s)
ctest --test-dir build-cuda --output-on-failure > "$out/ctest.log" 2>&1
note "ctest on the GPU: rc=$? in $(( $(date +%s) - t0 )) s: $(grep -E 'tests passed|tests failed' "$out/ctest.log")"

# memcheck on a small gas run of the driver
t0=$(date +%s)
compute-sanitizer --tool memcheck --error-exitcode 9 build-cuda/apps/blastsim/blastsim -q \
  examples/gas_expansion/gas_expansion.toml domain.nx=64 domain.ny=64 time.end=2e-5 output.vtk=false \
  output.directory=/tmp/sanitizer_run > "$out/memcheck.log" 2>&1
note "compute-sanitizer memcheck (gas 64^2, 2e-5 s): rc=$? $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"
# memcheck on the FDEM solver: the fracturing determinism case and the colliding bars (contact)
compute-sanitizer --tool memcheck --error-exitcode 9 build-cuda/tests/fdem/test_fdem "[determinism],[F7]" \
  >> "$out/memcheck.log" 2>&1
note "compute-sanitizer memcheck (test_fdem [determinism],[F7]): rc=$? $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"
# memcheck on the coupler: masks, cells changing state, I1 and the shock reflected by an immersed rock block (I2)
compute-sanitizer --tool memcheck --error-exitcode 9 build-cuda/tests/ibm/test_ibm "[masks],[transitions],[I1],[I2]" \
  >> "$out/memcheck.log" 2>&1
note "compute-sanitizer memcheck (test_ibm [masks],[transitions],[I1],[I2]): rc=$? $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"

# memcheck on a small coupled case (the single-hole step, ring mesh, 96 x 96 cells: every coupling kernel)
compute-sanitizer --tool memcheck --error-exitcode 9 build-cuda/apps/bench/blastsim-bench-coupled --cases=96:0.05 --steps=2 \
  --warmup=3 >> "$out/memcheck.log" 2>&1
note "compute-sanitizer memcheck (coupled single-hole, 96^2): rc=$? $(grep -E 'ERROR SUMMARY' "$out/memcheck.log" | tail -1)"

sizes=${GPU_BENCH_SIZES:-1250,2500,5001}
build-cuda/apps/bench/blastsim-bench-cip --sizes="$sizes" --steps=20 > "$out/bench_cip.log" 2>&1
note "bench_cip rc=$?"
cat "$out/bench_cip.log" >> "$summary"
if [ -x build-cuda/apps/bench/blastsim-bench-fdem ]; then
  build-cuda/apps/bench/blastsim-bench-fdem --sizes="${GPU_FDEM_SIZES:-187,512,1024}" --steps=50 \
    > "$out/bench_fdem.log" 2>&1
  note "bench_fdem rc=$?"
  cat "$out/bench_fdem.log" >> "$summary"
fi
if [ -x build-cuda/apps/bench/blastsim-bench-coupled ]; then
  # The coupled single-hole step phase by phase (ring mesh: no Gmsh needed): quarter size and paper size.
  # Twice: the gas step's kernel groups fused (the GPU's default) and launched one by one (same bytes, G12).
  for fusion in --fused --separate; do
    build-cuda/apps/bench/blastsim-bench-coupled --cases="${GPU_COUPLED_CASES:-2501:0.019,5001:0.0095}" --steps=20 \
      --kernels "$fusion" >> "$out/bench_coupled.log" 2>&1
    note "bench_coupled $fusion rc=$?"
  done
  cat "$out/bench_coupled.log" >> "$summary"
fi

# Per-kernel time, DRAM bytes, registers and occupancy of one whole coupled step at quarter size (Nsight
# Compute; after 3 warm-up steps of about 45 launches each): the most expensive kernels and why.
if [ "${1:-}" != quick ] && command -v ncu > /dev/null; then
  ncu --csv --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,launch__registers_per_thread,sm__warps_active.avg.pct_of_peak_sustained_active \
    --launch-skip 150 --launch-count 50 build-cuda/apps/bench/blastsim-bench-coupled --cases=2501:0.019 --steps=1 \
    --warmup=3 --fused > "$out/ncu_coupled.csv" 2>&1
  note "ncu rc=$? (per-kernel table in ncu_coupled.csv)"
fi
echo "==== summary"
cat "$summary"
