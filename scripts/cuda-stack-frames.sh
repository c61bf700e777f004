#!/usr/bin/env bash
# Registers, spills and stack frames of the CUDA kernels of the three libraries (ptxas -v; no GPU needed).
# A frame of hundreds of bytes means the compiler copied the kernel's argument (its views) to local memory,
# usually because a member was picked by a run-time index or a run-time choice between references; every field
# access then goes through local memory (docs/performance.md, "Local memory").
# Usage: scripts/cuda-stack-frames.sh          every kernel with a stack frame or a spill (sm_90a)
#        scripts/cuda-stack-frames.sh --all    every kernel: registers, spill stores/loads, frame, functors
#        ARCH=90 scripts/cuda-stack-frames.sh  another target (default 90a: the H100/H200)
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
[ "${1:-}" = "--all" ] && all=1
arch=${ARCH:-90a}
nvcc=/usr/local/cuda/bin/nvcc
[ -x "$nvcc" ] || { echo "cuda-stack-frames: no nvcc at $nvcc" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for src in libcip/src/*.cpp libfdem/src/{rock_solver,contact_search,rock_probes,fragment_labels,in_situ_setup}.cpp libibm/src/*.cpp; do
  "$nvcc" -DBLASTSIM_BACKEND_CUDA=1 -Ilibcip/include -Ilibfdem/include -Ilibibm/include -Icore/include -O3 -DNDEBUG \
    "--generate-code=arch=compute_${arch},code=sm_${arch}" --extended-lambda --expt-relaxed-constexpr -std=c++17 -x cu \
    -c "$src" -o "$tmp/k.o" -Xptxas -v > "$tmp/$(basename "$src").txt" 2>&1
done
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" - "$all" "$arch" "$tmp"/*.txt <<'PY'
import pathlib, re, subprocess, sys
show_all, arch = sys.argv[1] == "1", sys.argv[2]
# Wrappers of the launchers and Thrust's own types: not the kernel's functors.
skip = {"Flatten2D", "FusedCells", "Transformed", "FillWith", "CellPart", "IndexBox"}
rows, flagged = [], 0
for path in sys.argv[3:]:
    lines = pathlib.Path(path).read_text().splitlines()
    for k, line in enumerate(lines):
        m = re.search(r"Compiling entry function '([^']*)'", line)
        if not m:
            continue
        info = " ".join(lines[k + 1:k + 5])
        num = lambda pat: int(g.group(1)) if (g := re.search(pat, info)) else 0
        frame, stores, loads = num(r"(\d+) bytes stack frame"), num(r"(\d+) bytes spill stores"), num(r"(\d+) bytes spill loads")
        regs = num(r"Used (\d+) registers")
        name = subprocess.run(["c++filt", m.group(1)], capture_output=True, text=True).stdout
        if "blastsim" not in name:
            continue  # Thrust's and CUB's own kernels (fills, sorts, scans) instantiated for our types
        # The blastsim types in the name, in order, without the launchers' wrappers.
        funcs = []
        for t in re.findall(r"blastsim::(?:[a-z]+::)*(?:\(anonymous namespace\)::)?([A-Z][A-Za-z0-9]+)", name):
            if t not in skip and t not in funcs:
                funcs.append(t)
        if "lambda" in name and not funcs:
            funcs = ["(lambda)"]
        bad = frame > 0 or stores > 0 or loads > 0
        flagged += bad
        if show_all or bad:
            rows.append((pathlib.Path(path).stem, regs, stores, loads, frame, " ".join(funcs[:4]) or name[:60]))
rows.sort()
print(f"{'source':<24} {'regs':>5} {'spill st':>9} {'spill ld':>9} {'frame':>6}  functors (sm_{arch})")
for r in rows:
    print(f"{r[0]:<24} {r[1]:>5} {r[2]:>9} {r[3]:>9} {r[4]:>6}  {r[5]}")
print(f"cuda-stack-frames: {len(rows)} kernel(s) listed, {flagged} with a stack frame or a spill")
PY
