#!/usr/bin/env bash
# Lists the CUDA kernels of the three libraries whose threads keep a stack frame in local memory (ptxas -v,
# sm_90; no GPU needed). A frame of hundreds of bytes means the compiler copied the kernel's argument (its
# views) to local memory, usually because a member was picked by a run-time index or a run-time choice between
# references; every field access then goes through local memory (docs/performance.md, "Local memory").
# Usage: scripts/cuda-stack-frames.sh            (prints "bytes  kernel  source" for every frame > 0 bytes)
set -euo pipefail
cd "$(dirname "$0")/.."
nvcc=/usr/local/cuda/bin/nvcc
[ -x "$nvcc" ] || { echo "cuda-stack-frames: no nvcc at $nvcc" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for src in libcip/src/*.cpp libfdem/src/rock_solver.cpp libibm/src/coupler.cpp; do
  "$nvcc" -DBLASTSIM_BACKEND_CUDA=1 -Ilibcip/include -Ilibfdem/include -Ilibibm/include -Icore/include -O3 -DNDEBUG \
    --generate-code=arch=compute_90,code=sm_90 --extended-lambda --expt-relaxed-constexpr -std=c++17 -x cu \
    -c "$src" -o "$tmp/k.o" -Xptxas -v > "$tmp/$(basename "$src").txt" 2>&1
done
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" - "$tmp"/*.txt <<'PY'
import pathlib, re, subprocess, sys
rows = 0
for path in sys.argv[1:]:
    lines = pathlib.Path(path).read_text().splitlines()
    for k, line in enumerate(lines):
        m = re.search(r"Compiling entry function '([^']*)'", line)
        if not m:
            continue
        frame = next((int(f.group(1)) for f in (re.search(r"(\d+) bytes stack frame", l) for l in lines[k + 1:k + 4]) if f), 0)
        if frame == 0:
            continue
        name = subprocess.run(["c++filt", m.group(1)], capture_output=True, text=True).stdout
        kernels = sorted(set(re.findall(r"(?:detail|namespace\))::([A-Z][A-Za-z]+)", name))) or [name[:80]]
        print(f"{frame:6d}  {' '.join(kernels)}  {pathlib.Path(path).stem}")
        rows += 1
print(f"cuda-stack-frames: {rows} kernel(s) with a stack frame")
PY
