#!/usr/bin/env bash
# Strong scaling of the CPU backend: builds the coupled and gas benchmarks (CPU backend, no VTK, no Gmsh: the
# coupled benchmark meshes its rock in rings), runs each at 1, 2, 4, ... threads up to MAX_THREADS, REPEATS times
# (default 2), and prints the tables of docs/performance.md "Threads": the best wall time a step of the repeats,
# the speed-up over one thread and the parallel efficiency. On this machine, or on the GPU machine's 16 cores in
# one device call carrying .deps (scripts/device-deps.sh): `bash scripts/cpu-scaling.sh 16 420` (about 4 min).
# Usage: [REPEATS=N] scripts/cpu-scaling.sh [MAX_THREADS [SECONDS]]   (default: nproc, 540 s; runs that would
#        pass the deadline are left out and say so). Tables to $OUT/cpu-scaling.md (default out/), runs' output
#        to $OUT/cpu-scaling.log.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
max=${1:-$(nproc)}
budget=${2:-540}
repeats=${REPEATS:-2}
# Whole numbers of at most 6 digits (so that the shell's arithmetic cannot overflow), then their ranges: the
# thread counts double up to MAX_THREADS, and every run of the REPEATS must fit the SECONDS.
for value in "$max" "$budget" "$repeats"; do
  case "$value" in
    "" | *[!0-9]* | ???????*)
      echo "usage: [REPEATS=N] scripts/cpu-scaling.sh [MAX_THREADS [SECONDS]] (whole numbers; got '$value')" >&2
      exit 2 ;;
  esac
done
max=$((10#$max)) budget=$((10#$budget)) repeats=$((10#$repeats))
if [ "$max" -lt 1 ] || [ "$max" -gt 1024 ] || [ "$repeats" -lt 1 ] || [ "$repeats" -gt 20 ] ||
   [ "$budget" -lt 60 ] || [ "$budget" -gt 86400 ]; then
  echo "cpu-scaling: MAX_THREADS $max must be in 1..1024, REPEATS $repeats in 1..20, SECONDS $budget in 60..86400" >&2
  exit 2
fi
deadline=$(($(date +%s) + budget))
out=${OUT:-$PWD/out}
mkdir -p "$out"
report=$out/cpu-scaling.md
log=$out/cpu-scaling.log
: > "$log"

build="build-cpu-scaling"
prefix=()
[ -d .deps/usr ] && prefix=(-DCMAKE_PREFIX_PATH="$PWD/.deps/usr")
t0=$(date +%s)
if ! { cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DBLASTSIM_ENABLE_CUDA=OFF \
         -DBLASTSIM_ENABLE_VTK=OFF -DBLASTSIM_ENABLE_GMSH=OFF -DBLASTSIM_BUILD_TESTS=OFF -DBLASTSIM_FMT_HEADER_ONLY=ON \
         "${prefix[@]}" >> "$log" 2>&1 &&
       cmake --build "$build" -j"$(nproc)" --target blastsim-bench-coupled blastsim-bench-cip >> "$log" 2>&1; }; then
  tail -30 "$log" >&2
  echo "cpu-scaling: the build failed (log: $log)" >&2
  exit 1
fi
echo "cpu-scaling: built in $(( $(date +%s) - t0 )) s" | tee -a "$log"

threads=()
for ((t = 1; t < max; t *= 2)); do threads+=("$t"); done
threads+=("$max")
# Each run on its own cores, one thread a core, so that the counts compare (OpenMP 4.0 placement).
export OMP_PROC_BIND=close OMP_PLACES=cores

# run NAME SECONDS COMMAND...: its output into the log; nothing when the deadline is too near.
run() {
  local name=$1 cap=$2 left
  shift 2
  left=$((deadline - $(date +%s) - 5))
  [ "$left" -lt "$cap" ] && cap=$left
  if [ "$cap" -lt 5 ]; then
    echo "cpu-scaling: $name left out (deadline)" | tee -a "$log"
    return 1
  fi
  echo "== $name" >> "$log"
  timeout "$cap" "$@" > "$out/run.txt" 2>&1
  local rc=$?
  cat "$out/run.txt" >> "$log"
  [ $rc -eq 0 ] || { echo "cpu-scaling: $name: rc=$rc" | tee -a "$log"; return 1; }
}

# keep ARRAY KEY VALUE: the smaller of the value kept and VALUE (the best of the repeats).
keep() {
  local -n kept=$1
  [ -z "$3" ] && return
  local old=${kept[$2]:-}
  if [ -z "$old" ] || awk -v a="$3" -v b="$old" 'BEGIN { exit !(a < b) }'; then kept[$2]=$3; fi
}
# shellcheck disable=SC2034  # read through the namerefs of keep() and row()
declare -A coupled gas
for t in "${threads[@]}"; do
  for ((r = 1; r <= repeats; ++r)); do
    if run "coupled, $t threads, run $r" 240 env OMP_NUM_THREADS="$t" "$build/apps/bench/blastsim-bench-coupled" \
        --cases=280:0.03,560:0.015 --steps=20 --gas-load=faces; then
      mapfile -t ms < <(sed -n 's/^step: \([0-9.]*\) ms wall without profiling.*/\1/p' "$out/run.txt")
      keep coupled "$t,280" "${ms[0]:-}"
      keep coupled "$t,560" "${ms[1]:-}"
    fi
    if run "gas, $t threads, run $r" 120 env OMP_NUM_THREADS="$t" "$build/apps/bench/blastsim-bench-cip" \
        --sizes=400,1000 --steps=20 --transport=conservative; then
      mapfile -t ms < <(awk '$1 == "conservative" {print $3}' "$out/run.txt")
      keep gas "$t,400" "${ms[0]:-}"
      keep gas "$t,1000" "${ms[1]:-}"
    fi
  done
done
rm -f "$out/run.txt"

# row THREADS ARRAY KEY: wall time, speed-up and efficiency against one thread.
row() {
  local -n times=$2
  local t=$1 base=${times[1,$3]:-} v=${times[$1,$3]:-}
  if [ -z "$v" ]; then
    echo "| $t | (not run) | | |"
  elif [ -z "$base" ]; then
    echo "| $t | $v ms | | |"
  else
    awk -v t="$t" -v v="$v" -v b="$base" \
      'BEGIN { printf "| %d | %.2f ms | %.2f | %.0f %% |\n", t, v, b / v, 100 * b / v / t }'
  fi
}
{
  echo "cpu-scaling: $(date -u +%Y-%m-%dT%H:%MZ), tree $(git rev-parse --short HEAD 2>/dev/null || echo unknown)," \
       "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))," \
       "OMP_PROC_BIND=$OMP_PROC_BIND OMP_PLACES=$OMP_PLACES, best of $repeats runs"
  for c in 280 560; do
    echo
    size="280^2 cells, 30 mm triangles"
    [ $c = 560 ] && size="560^2 cells, 15 mm triangles"
    echo "Coupled step ($size, blastsim-bench-coupled --steps=20 --gas-load=faces, wall time a step without profiling):"
    echo
    echo "| threads | step | speed-up | efficiency |"
    echo "|---|---|---|---|"
    for t in "${threads[@]}"; do row "$t" coupled "$c"; done
  done
  for n in 400 1000; do
    echo
    echo "Gas step (${n}^2 cells, blastsim-bench-cip --steps=20 --transport=conservative):"
    echo
    echo "| threads | step | speed-up | efficiency |"
    echo "|---|---|---|---|"
    for t in "${threads[@]}"; do row "$t" gas "$n"; done
  done
} | tee "$report"
