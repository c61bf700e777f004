#!/usr/bin/env bash
# The single-hole blast (examples/single_hole) in a stressed rock mass: in-situ sigma_1 along x and sigma_3 along y
# with sigma_1 / sigma_3 = 1, 2, 4 (sigma_3 = -2 MPa), held on the outer circle (a viscous boundary: the disc stands
# for a rock mass that goes on), Weibull-scattered joint strength (modulus 5) with seeds 1-3 per ratio, to
# 1.2 ms. Reports each run's crack length in 30-degree sectors of direction from the hole (crack_rose.csv) and the
# share within 30 degrees of the sigma_1 axis (4 of 12 sectors: one third if the cracks ignore the stress);
# docs/single-hole.md "In a stressed rock mass". About 25 minutes on 2 cores.
# Usage: scripts/stress-blast-study.sh [OUT_DIR]   (default stress_blast_study; any folder name). The case is read
# by the driver (--check) before anything runs (exit 2 with its message); a run that fails is reported and left out
# of the table, and the other runs go on; a finished run is not run again.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
[ $# -le 1 ] || { echo "usage: scripts/stress-blast-study.sh [OUT_DIR]" >&2; exit 2; }
out="${1:-stress_blast_study}"
[ -n "$out" ] || { echo "stress-blast-study: OUT_DIR is empty" >&2; exit 2; }
if [ -e "$out" ] && [ ! -d "$out" ]; then echo "stress-blast-study: $out exists and is not a folder" >&2; exit 2; fi
blastsim="${BLASTSIM:-$repo/build-cpu/apps/blastsim/blastsim}"
[ -x "$blastsim" ] || { echo "stress-blast-study: build the driver first (scripts/run-tests.sh)" >&2; exit 1; }
# The folder as a TOML string (output.directory), whatever characters its name holds.
toml_string() { local s=${1//\\/\\\\}; s=${s//\"/\\\"}; printf '"%s"' "$s"; }
run_case() {  # run_case RATIO SEED DIR [--check]: the driver on one run of the study
  "$blastsim" ${4:+"$4"} "$repo/examples/single_hole/single_hole.toml" time.end=1.2e-3 output.vtk=false \
    "output.directory=$(toml_string "$3")" 'rock.viscous_boundary=[{boundary = "outer"}]' \
    "rock.in_situ_stress.sigma_xx=-$((2 * $1)).0e6" rock.in_situ_stress.sigma_yy=-2.0e6 \
    rock.heterogeneity.modulus=5 "rock.heterogeneity.seed=$2"
}
if ! err=$(run_case 4 1 "$out/check" --check 2>&1 >/dev/null); then
  echo "stress-blast-study: $err" >&2
  exit 2
fi
mkdir -p "$out"
for ratio in 1 2 4; do
  for seed in 1 2 3; do
    name="ratio${ratio}_seed${seed}"
    [ -f "$out/$name/crack_rose.csv" ] && [ -f "$out/$name.done" ] && continue
    rm -f "$out/$name.done"
    if run_case "$ratio" "$seed" "$out/$name" > "$out/$name.log" 2>&1; then
      touch "$out/$name.done"
    else
      echo "stress-blast-study: $name failed (exit $?; see $out/$name.log); the other runs go on" >&2
    fi
  done
done
python3 - "$out" <<'PY'
import csv, math, os, statistics, sys
out = sys.argv[1]
print("ratio  seed  crack length [m] by sector start (deg) 0..330                            total   near sigma_1")
for ratio in (1, 2, 4):
    shares = []
    for seed in (1, 2, 3):
        path = os.path.join(out, f"ratio{ratio}_seed{seed}", "crack_rose.csv")
        if not os.path.exists(os.path.join(out, f"ratio{ratio}_seed{seed}.done")) or not os.path.exists(path):
            print(f"{ratio:5d} {seed:5d}  (no finished run)")
            continue
        rows = [r for r in csv.DictReader(open(path)) if r["hole"] == "0"]
        rose = [float(r["crack_length_m"]) for r in rows]
        total = sum(rose)
        near = sum(rose[k] for k in (0, 5, 6, 11))  # directions within 30 deg of the x axis (sigma_1)
        shares.append(near / total if total > 0 else float("nan"))
        print(f"{ratio:5d} {seed:5d}  " + " ".join(f"{v:5.2f}" for v in rose) + f"  {total:6.2f}  {100 * shares[-1]:5.1f} %")
    if not shares:
        print(f"ratio {ratio}: no finished run")
        continue
    print(f"ratio {ratio}: share of the crack length within 30 deg of sigma_1: mean {100 * statistics.mean(shares):.1f} %, "
          f"seeds {', '.join(f'{100 * s:.1f}' for s in shares)} % (no preference: 33.3 %)")
PY
