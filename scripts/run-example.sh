#!/usr/bin/env bash
# The example command: installs what is missing, builds the driver (preset "cpu") and runs the bundled
# single-hole blast (examples/single_hole/single_hole.toml) at its default size, then draws its figures.
# Usage: scripts/run-example.sh [key=value overrides...]
# Results go to ./single_hole_output: VTK series for ParaView, CSV series, summary.txt, PNG figures.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
cmake --preset cpu -S "$root" >/dev/null
cmake --build "$root/build-cpu" -j2 --target blastsim
"$root/build-cpu/apps/blastsim/blastsim" "$root/examples/single_hole/single_hole.toml" "$@"
# Figures from the VTK and CSV output (Debian's python3-matplotlib and python3-vtk9; /usr/bin/python3 is
# Debian's interpreter). The output folder is the input's unless overridden on the command line.
out=single_hole_output
for arg in "$@"; do
  case "$arg" in output.directory=*) out="${arg#output.directory=}"; out="${out%\"}"; out="${out#\"}" ;; esac
done
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" "$root/scripts/plot-single-hole.py" "$out"
"$py" "$root/scripts/plot-analysis.py" "$out"
