#!/usr/bin/env bash
# Toro's 2-D cylindrical explosion with OpenFOAM's rhoCentralFoam and with blastsim's gas solver, one thread each:
# wall time and density L1 error against the same radial reference, per grid (docs/performance.md, "The gas
# against rhoCentralFoam").
# Usage: scripts/compare-openfoam.sh [build dir (default build-cpu)] [n ...]   (default n: 100 141 200 283 400)
# Needs the Debian package openfoam (v1912: blockMesh, setFields, rhoCentralFoam) and a built
# blastsim-bench-explosion. The OpenFOAM case follows the rhoCentralFoam shockTube tutorial (Kurganov flux,
# van Leer reconstruction, maxCo 0.2, air with mu = 0) in dimensional form: rho 1 / 0.125 kg/m3, p 1e5 / 1e4 Pa,
# so that t = 0.25 of Toro's units is 0.25 / sqrt(1e5) s. The cases are written under $WORK (default a
# temporary folder).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-cpu}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(100 141 200 283 400)
bench="$build/apps/bench/blastsim-bench-explosion"
[ -x "$bench" ] || { echo "compare-openfoam: no $bench (build the target blastsim-bench-explosion)" >&2; exit 1; }
for tool in blockMesh setFields rhoCentralFoam; do
  command -v $tool > /dev/null || { echo "compare-openfoam: no $tool (apt-get install openfoam)" >&2; exit 1; }
done
# The Debian package keeps OpenFOAM's etc folder here; its programs look for it through these variables.
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
export FOAM_ETC=${FOAM_ETC:-$WM_PROJECT_DIR/etc}
work=${WORK:-$(mktemp -d)}
t_end=$(python3 -c "print(repr(0.25 / 1e5 ** 0.5))")
header() {  # FoamFile header: class, object
  printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n    object %s;\n}\n' "$1" "$2"
}
field() {  # volScalarField or volVectorField: name, class, dimensions, value
  header "$2" "$1"
  printf 'dimensions %s;\ninternalField uniform %s;\n' "$3" "$4"
  printf 'boundaryField\n{\n    sides { type zeroGradient; }\n    frontAndBack { type empty; }\n}\n'
}
echo "OpenFOAM rhoCentralFoam (one process) and blastsim (OMP_NUM_THREADS=1), to t = 0.25 ($t_end s); cases in $work"
printf '%6s %14s %12s\n' n "OpenFOAM s" "density L1"
for n in "${sizes[@]}"; do
  c="$work/of$n"
  rm -rf "$c" && mkdir -p "$c/system" "$c/constant" "$c/0"
  { header dictionary blockMeshDict
    printf 'convertToMeters 1;\nvertices ((-1 -1 -0.01) (1 -1 -0.01) (1 1 -0.01) (-1 1 -0.01) (-1 -1 0.01) (1 -1 0.01) (1 1 0.01) (-1 1 0.01));\n'
    printf 'blocks (hex (0 1 2 3 4 5 6 7) (%d %d 1) simpleGrading (1 1 1));\n' "$n" "$n"
    printf 'boundary (sides { type patch; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)); }\n'
    printf '          frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); });\n'; } > "$c/system/blockMeshDict"
  { header dictionary controlDict
    printf 'application rhoCentralFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime %s;\n' "$t_end"
    printf 'deltaT 1e-8;\nwriteControl adjustable;\nwriteInterval %s;\nwriteFormat ascii;\nwritePrecision 12;\n' "$t_end"
    printf 'writeCompression off;\ntimeFormat general;\ntimePrecision 9;\nrunTimeModifiable false;\n'
    printf 'adjustTimeStep yes;\nmaxCo 0.2;\nmaxDeltaT 1;\n'; } > "$c/system/controlDict"
  { header dictionary fvSchemes
    printf 'fluxScheme Kurganov;\nddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n'
    printf 'divSchemes { default none; div(tauMC) Gauss linear; }\nlaplacianSchemes { default Gauss linear corrected; }\n'
    printf 'interpolationSchemes { default linear; reconstruct(rho) vanLeer; reconstruct(U) vanLeerV; reconstruct(T) vanLeer; }\n'
    printf 'snGradSchemes { default corrected; }\n'; } > "$c/system/fvSchemes"
  { header dictionary fvSolution
    printf 'solvers\n{\n    "(rho|rhoU|rhoE)" { solver diagonal; }\n'
    printf '    U { solver smoothSolver; smoother GaussSeidel; nSweeps 2; tolerance 1e-09; relTol 0.01; }\n'
    printf '    e { solver smoothSolver; smoother GaussSeidel; nSweeps 2; tolerance 1e-10; relTol 0; }\n}\n'; } > "$c/system/fvSolution"
  { header dictionary setFieldsDict
    printf 'defaultFieldValues (volVectorFieldValue U (0 0 0) volScalarFieldValue T 278.746 volScalarFieldValue p 10000);\n'
    printf 'regions (cylinderToCell { p1 (0 0 -1); p2 (0 0 1); radius 0.4;\n'
    printf '          fieldValues (volScalarFieldValue T 348.432 volScalarFieldValue p 100000); });\n'; } > "$c/system/setFieldsDict"
  { header dictionary thermophysicalProperties
    printf 'thermoType { type hePsiThermo; mixture pureMixture; transport const; thermo hConst;\n'
    printf '             equationOfState perfectGas; specie specie; energy sensibleInternalEnergy; }\n'
    printf 'mixture { specie { molWeight 28.96; } thermodynamics { Cp 1004.5; Hf 0; } transport { mu 0; Pr 1; } }\n'; } \
    > "$c/constant/thermophysicalProperties"
  { header dictionary turbulenceProperties; printf 'simulationType laminar;\n'; } > "$c/constant/turbulenceProperties"
  field p volScalarField "[1 -1 -2 0 0 0 0]" 10000 > "$c/0/p"
  field T volScalarField "[0 0 0 1 0 0 0]" 278.746 > "$c/0/T"
  field U volVectorField "[0 1 -1 0 0 0 0]" "(0 0 0)" > "$c/0/U"
  (cd "$c" && blockMesh > log.blockMesh 2>&1 && setFields > log.setFields 2>&1) \
    || { echo "compare-openfoam: mesh or fields failed for n = $n (see $c)" >&2; exit 1; }
  start=$(date +%s.%N)
  (cd "$c" && rhoCentralFoam > log.rhoCentralFoam 2>&1) || { echo "compare-openfoam: rhoCentralFoam failed (see $c/log.rhoCentralFoam)" >&2; exit 1; }
  seconds=$(python3 -c "import sys; print('%.2f' % ($(date +%s.%N) - $start))")
  last=$(ls -1 "$c" | grep -E '^[0-9.e+-]+$' | grep -v '^0$' | sort -g | tail -1)
  l1=$("$bench" --openfoam-rho="$c/$last/rho" --n="$n" | sed 's/.*density L1 //')
  printf '%6d %14s %12s   (time folder %s)\n' "$n" "$seconds" "$l1" "$last"
done
echo "blastsim, default Courant number:"
OMP_NUM_THREADS=1 "$bench" --sizes="$(IFS=,; echo "${sizes[*]}")"
