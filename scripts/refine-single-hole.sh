#!/usr/bin/env bash
# Refinement study (validation S5) of the single-hole example: runs the default input at several gas-cell /
# triangle sizes (same materials, gas states and end time) and tabulates broken joints, crack length, the
# events of summary.txt (the blast gas's arrival at the outer surface and its outflow speed too), the time each
# run reached (a run that stops with exit 3 is tabulated to where it stopped) and the energy budget. Usage: scripts/refine-single-hole.sh [OUTPUT_ROOT] [LEVELS...]
# A level is NX:ELEMENT_SIZE (cells along each side of the 2.24 m grid, triangle size in m). The default levels
# are 224:0.0375 280:0.03 350:0.024 420:0.02 (10, 8, 6.4 and 5.3 mm cells); the two finest take about 6 and
# 15 minutes on 2 cores.
# Every argument is checked, and every level's case read by the driver (--check), before anything runs (exit 2 with
# a message); a level whose run fails is tabulated with what it wrote, and the others still run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
usage="usage: scripts/refine-single-hole.sh [OUTPUT_ROOT] [NX:ELEMENT_SIZE ...]  (e.g. 280:0.03)"
out="${1:-single_hole_refinement}"
shift || true
levels=("$@")
[ ${#levels[@]} -gt 0 ] || levels=(224:0.0375 280:0.03 350:0.024 420:0.02)
[ -n "$out" ] || { echo "refine-single-hole: OUTPUT_ROOT is empty; $usage" >&2; exit 2; }
if [ -e "$out" ] && [ ! -d "$out" ]; then echo "refine-single-hole: $out exists and is not a folder" >&2; exit 2; fi
for level in "${levels[@]}"; do
  if ! [[ "$level" =~ ^[0-9]{1,6}:[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]]; then
    echo "refine-single-hole: level '$level' is not NX:ELEMENT_SIZE (a whole number of cells, a size in m); $usage" >&2
    exit 2
  fi
done
exe="$root/build-cpu/apps/blastsim/blastsim"
[ -x "$exe" ] || { echo "build the driver first: cmake --preset cpu && cmake --build --preset cpu -j2" >&2; exit 1; }
# The folder as a TOML string (output.directory), whatever characters its name holds.
toml_string() { local s=${1//\\/\\\\}; s=${s//\"/\\\"}; printf '"%s"' "$s"; }
case_of() {  # case_of LEVEL DIR: the driver's arguments of one level
  local nx="${1%%:*}" h="${1##*:}"
  printf '%s\n' "$root/examples/single_hole/single_hole.toml" "domain.nx=$nx" "domain.ny=$nx" \
    "rock.mesh.element_size=$h" "output.directory=$(toml_string "$2")" output.vtk=false output.progress_interval=60
}
for level in "${levels[@]}"; do
  mapfile -t args < <(case_of "$level" "$out/check")
  if ! err=$("$exe" --check "${args[@]}" 2>&1 >/dev/null); then
    echo "refine-single-hole: level $level: $err" >&2
    exit 2
  fi
done
mkdir -p "$out"
for level in "${levels[@]}"; do
  nx="${level%%:*}" h="${level##*:}"
  dir="$out/nx${nx}_h${h}"
  mapfile -t args < <(case_of "$level" "$dir")
  start=$(date +%s)
  rc=0
  "$exe" "${args[@]}" >"$dir.log" 2>&1 || rc=$?
  echo "$level $(( $(date +%s) - start )) s rc=$rc" >>"$out/wall_times.txt"
done
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" - "$out" <<'PY'
import csv, pathlib, re, sys
root = pathlib.Path(sys.argv[1])
times = dict(l.split()[0:2] for l in (root / "wall_times.txt").read_text().splitlines())
print("| cells (size) | triangles (size) | reached ms | broken joints | crack length m | first crack ms | gas leaves ms | gas speed m/s | blast gas arrives ms | blast gas speed m/s | budget residual / initial | residual / gas work | wall s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
def read(path):
    try:
        return path.read_text()
    except OSError:
        return ""
for d in sorted(root.glob("nx*_h*"), key=lambda p: int(re.match(r"nx(\d+)", p.name).group(1))):
    if not d.is_dir(): continue
    nx, h = re.match(r"nx(\d+)_h(.+)", d.name).groups()
    try:
        rows = list(csv.DictReader(open(d / "coupling_series.csv")))
    except OSError:
        rows = []
    if not rows:  # the run wrote no row: say so, and go on with the other levels
        print(f"| {nx}^2 | ({h} m) | no output (see {d.name}.log) |" + " |" * 10 + f" {times.get(nx + ':' + h, '?')} |")
        continue
    last = rows[-1]
    summary = read(d / "summary.txt")
    def event(label):
        m = re.search(label + r": [0-9.e+-]+ s \(([0-9.]+) ms\)", summary)
        return m.group(1) if m else "-"
    speed = re.search(r"nominal gas speed there: ([0-9.]+) m/s", summary)
    blast_speed = re.search(r"blast gas outflow speed: ([0-9.]+) m/s", summary)
    log = read(root / (d.name + ".log"))
    tri_match = re.search(r"rock (\d+) triangles", log)
    tri = tri_match.group(1) if tri_match else "?"
    work = float(last["gas_work_on_rock_J_per_m"])
    res = float(last["budget_residual_J_per_m"])
    print(f"| {nx}^2 ({2.24 / int(nx) * 1e3:.1f} mm) | {tri} ({float(h) * 1e3:.1f} mm) | {float(last['time_s']) * 1e3:.3f} | "
          f"{last['broken_joints']} | {float(last['crack_length_m']):.2f} | {event('first crack')} | "
          f"{event('gas leaves the rock.s outer surface')} | {speed.group(1) if speed else '-'} | "
          f"{event('blast gas reaches the rock.s outer surface')} | {blast_speed.group(1) if blast_speed else '-'} | "
          f"{float(last['budget_relative']):+.2e} | {f'{res / work:+.2%}' if work != 0 else '-'} | "
          f"{times.get(nx + ':' + h, '?')} |")
PY
