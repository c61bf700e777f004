#!/usr/bin/env bash
# The example command: installs what is missing, builds the driver (preset "cpu") and runs the bundled
# example at its default size. Usage: scripts/run-example.sh [key=value overrides...]
# Results go to ./gas_expansion_output (VTK series for ParaView, CSV probes and time series, PNG plots).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
cmake --preset cpu -S "$root" >/dev/null
cmake --build "$root/build-cpu" -j2 --target blastsim
"$root/build-cpu/apps/blastsim/blastsim" "$root/examples/gas_expansion/gas_expansion.toml" "$@"
# Plots of the CSV output (Debian's python3-matplotlib; /usr/bin/python3 is Debian's interpreter).
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" "$root/scripts/plot-gas-results.py" gas_expansion_output
