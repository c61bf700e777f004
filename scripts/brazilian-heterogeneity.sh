#!/usr/bin/env bash
# The Brazilian disc (examples/brazilian_disc) with heterogeneous joint strength: peak load and Brazilian
# tensile strength 2 P / (pi D) of uniform rock and of Weibull moduli 10, 5 and 3 (seeds 1-3 each), the trend
# of docs/fdem-solver.md "Heterogeneous strength". About 4 minutes on 2 cores.
# Usage: scripts/brazilian-heterogeneity.sh [OUT_DIR]   (default brazilian_heterogeneity)
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-brazilian_heterogeneity}"
mkdir -p "$out"
blastsim="$repo/build-cpu/apps/blastsim/blastsim"
[ -x "$blastsim" ] || { echo "brazilian-heterogeneity: build the driver first (scripts/run-tests.sh)" >&2; exit 1; }
run() {  # name, then overrides
  local name=$1
  shift
  "$blastsim" -q "$repo/examples/brazilian_disc/brazilian_disc.toml" output.vtk=false \
    "output.directory=\"$out/$name\"" "$@" > "$out/$name.log" 2>&1
  python3 - "$out/$name/rock_series.csv" "$name" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
p = max(abs(float(r["velocity0_reaction_y_N_per_m"])) for r in rows)  # top platen's reaction [N/m]
print(f"{sys.argv[2]:10s} peak load {p:.5g} N/m  Brazilian strength {2 * p / (math.pi * 0.1) / 1e6:.3f} MPa  "
      f"broken joints {rows[-1]['broken_joints']}")
PY
}
run uniform
for m in 10 5 3; do
  for s in 1 2 3; do run "m${m}_seed$s" rock.heterogeneity.modulus=$m rock.heterogeneity.seed=$s; done
done
