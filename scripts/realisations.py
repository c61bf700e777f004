#!/usr/bin/python3
"""Run one blastsim case N times on perturbed meshes and gather the spread of its main results.

Usage: scripts/realisations.py CASE.toml N [--remesh] [--jitter F] [--rotate] [--strength-seed] [--out DIR] [--blastsim PATH]
                               [--resume] [--collect-only] [--jobs J] [section.key=value ...]

Realisation K (K = 1..N) runs, one after another (J at once with --jobs J: each then with OMP_NUM_THREADS = cores / J
unless the environment sets it),
    blastsim -q CASE.toml rock.mesh.jitter=F rock.mesh.seed=K output.directory=DIR/seed_K [section.key=value ...]
with F = 0.03 unless --jitter says otherwise (--jitter 0 keeps the mesh). --remesh (Gmsh meshes) makes realisation K
Gmsh's mesh number K instead, rock.mesh.realisation=K with no jitter unless --jitter is given: meshes that share no
vertex, where jittered ones keep one topology (docs/fdem-solver.md, "Mesh realisations"). --rotate also turns the mesh of a disc
shape about its centre, rock.mesh.rotation = rotation_deg(K), so that the polygons of its circles sit differently
on the gas grid in each realisation; --strength-seed also sets
rock.heterogeneity.seed=K, for a case with a [rock.heterogeneity] table: docs/input.md); DIR defaults to realisations_<case stem> in the current directory
and blastsim to build-cpu/apps/blastsim/blastsim of this repository. The driver's own output goes to
DIR/seed_K/blastsim.log. --resume skips a seed whose summary.txt says the run reached time.end (read from the
overrides or the case file); --collect-only runs nothing and rebuilds the tables from the folders there.

From each run it takes the crack length and broken joints (last row of rock_series.csv), fragments, X50, X80 and the
crushed and cracked radius of hole 0 (last row of fragmentation_series.csv), and the time the gas leaves the
rock's outer surface (summary.txt, possibly "not reached"), the blast gas's front at 0.2 / 0.4 / 0.6 m and its
arrival at the outer surface (wall_series.csv, summary.txt; a run with the blasthole monitor) and the time the
run reached, and writes
  DIR/realisations.csv  one row per seed
  DIR/realisations.md   per quantity: runs, mean, sample standard deviation (n-1), min, max and coefficient of
                        variation (std / |mean|); printed too
Needs only Python 3 (/usr/bin/python3).
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
NOT_REACHED = "not reached"
# (column of realisations.csv, source file, column there, label in the table)
QUANTITIES = [
    ("crack_length_m", "rock_series.csv", "crack_length_m", "crack length [m]"),
    ("broken_joints", "rock_series.csv", "broken_joints", "broken joints"),
    ("fragments", "fragmentation_series.csv", "fragments", "fragments"),
    ("x50_m", "fragmentation_series.csv", "x50_m", "X50 [m]"),
    ("x80_m", "fragmentation_series.csv", "x80_m", "X80 [m]"),
    ("hole0_crushed_radius_m", "fragmentation_series.csv", "hole0_crushed_radius_m", "hole 0 crushed radius [m]"),
    ("hole0_cracked_radius_m", "fragmentation_series.csv", "hole0_cracked_radius_m", "hole 0 cracked radius [m]"),
]
EJECTION = ("ejection_time_s", "gas ejection time [s]")
# Times [s] (or "not reached") of the blast gas: its front (wall_series.csv, blast_gas_front_radius_m) first at
# these distances [m] from the hole centre, and its arrival at the outer surface (summary.txt).
FRONT_RADII = (0.2, 0.4, 0.6)
BLAST = [(f"blast_front_{round(100 * r)}cm_s", f"blast gas front at {r:g} m [s]") for r in FRONT_RADII] + \
        [("blast_arrival_s", "blast gas at the outer surface [s]"), ("end_s", "time reached [s]")]


def rotation_deg(k):
    """The mesh turn of realisation k under --rotate [deg]: 360 times the fractional part of k times the golden
    ratio's fractional part, angles spread evenly over the circle whatever the number of realisations."""
    return round(360.0 * ((k * (math.sqrt(5.0) - 1.0) / 2.0) % 1.0), 6)


def last_row(path):
    """The last row of a CSV file as a dict, or {} if the file is missing or has no rows."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except FileNotFoundError:
        return {}
    return rows[-1] if rows else {}


def end_time(case, overrides):
    """time.end of the run: from the overrides, else from the case file; None when it cannot be read."""
    for o in overrides:
        if o.startswith("time.end="):
            try:
                return float(o.split("=", 1)[1])
            except ValueError:
                return None
    try:
        import tomllib  # Python >= 3.11

        with open(case, "rb") as f:
            return float(tomllib.load(f)["time"]["end"])
    except ImportError:  # older Python: the first `end = ...` after [time]
        m = re.search(r"^\[time\][^\[]*?^\s*end\s*=\s*([-+0-9.eE]+)", Path(case).read_text(), re.M | re.S)
        return float(m.group(1)) if m else None
    except (OSError, KeyError, ValueError):
        return None


def complete(folder, end):
    """Whether folder holds a finished run: summary.txt written at (nearly) time.end, when that is known."""
    summary = folder / "summary.txt"
    if not summary.exists():
        return False
    m = re.search(r"summary at t = (\S+) s", summary.read_text())
    return end is None or (m is not None and float(m.group(1)) >= 0.999 * end)


def seed_command(args, blastsim, k, folder):
    """The driver's command line of realisation k, its output into folder."""
    command = [str(blastsim), "-q", args.case, f"rock.mesh.jitter={args.jitter}", f"rock.mesh.seed={k}",
               f"output.directory={folder.resolve()}", *args.overrides]
    if args.remesh:
        command.append(f"rock.mesh.realisation={k}")
    if args.rotate:
        command.append(f"rock.mesh.rotation={rotation_deg(k)}")
    if args.strength_seed:
        command.append(f"rock.heterogeneity.seed={k}")
    return command


def check_arguments(args, parser, out):
    """Everything that can be checked before a run: the files named, the output folder, and the case with every
    override, which the driver reads and validates (--check) as realisation 1 would; exits 2 with a message."""
    if not Path(args.case).is_file():
        parser.error(f"the case file {args.case} does not exist or is not a file")
    if out.exists() and not out.is_dir():
        parser.error(f"--out {out}: exists and is not a folder")
    if args.collect_only:
        return None
    blastsim = Path(args.blastsim) if args.blastsim else REPO / "build-cpu/apps/blastsim/blastsim"
    if not blastsim.is_file() or not os.access(blastsim, os.X_OK):
        parser.error(f"no blastsim program at {blastsim} (build it with scripts/run-tests.sh, or pass --blastsim)")
    command = seed_command(args, blastsim, 1, out / "seed_1")
    command.insert(1, "--check")
    checked = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if checked.returncode != 0:
        parser.error(f"blastsim refuses the case as realisation 1 would run it (exit {checked.returncode}):\n"
                     f"{checked.stderr.strip()}")
    return blastsim


def run_all(args, out, blastsim):
    end = end_time(args.case, args.overrides)
    env = dict(os.environ)
    if args.jobs > 1 and "OMP_NUM_THREADS" not in env:  # the cores shared among the runs at once
        env["OMP_NUM_THREADS"] = str(max(1, (os.cpu_count() or 1) // args.jobs))
    todo = []
    for k in range(1, args.n + 1):
        folder = out / f"seed_{k}"
        if args.resume and complete(folder, end):
            print(f"[{k}/{args.n}] seed {k}: complete run in {folder}, skipped", flush=True)
            continue
        folder.mkdir(parents=True, exist_ok=True)
        todo.append((k, folder, seed_command(args, blastsim, k, folder)))
    lock = threading.Lock()

    def run_one(item):
        k, folder, command = item
        with lock:
            print(f"[{k}/{args.n}] seed {k}: running into {folder}" + (" ..." if args.jobs == 1 else ""),
                  end=" " if args.jobs == 1 else "\n", flush=True)
        start = time.monotonic()
        with open(folder / "blastsim.log", "w") as log:
            rc = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env).returncode
        with lock:
            prefix = "" if args.jobs == 1 else f"[{k}/{args.n}] seed {k}: "
            print(f"{prefix}{'done' if rc == 0 else f'FAILED (exit {rc})'} in {time.monotonic() - start:.0f} s", flush=True)
            if rc != 0:
                print(f"  see {folder / 'blastsim.log'}", flush=True)
        return k, rc

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(run_one, todo))
    return sorted(k for k, rc in results if rc != 0)


def event_time(summary_text, label):
    """The time [s] summary.txt gives an event ("LABEL: 1.23e-03 s ..."), NOT_REACHED, or None if it has no line."""
    m = re.search(re.escape(label) + r": (not reached|\S+ s)", summary_text)
    if m is None:
        return None
    return NOT_REACHED if m.group(1) == NOT_REACHED else float(m.group(1).split()[0])


def collect(folder):
    """The row of realisations.csv of one run folder: numbers as floats, missing values as None."""
    row = {}
    for key, source, column, _ in QUANTITIES:
        value = last_row(folder / source).get(column)
        row[key] = float(value) if value not in (None, "") else None
    summary = folder / "summary.txt"
    text = summary.read_text() if summary.exists() else ""
    row[EJECTION[0]] = event_time(text, "gas leaves the rock's outer surface")
    # The blast gas (a run with the blasthole monitor and a traced gas); a run that stopped early reports the
    # time it reached, and what it did not reach by then as "not reached".
    try:
        with open(folder / "wall_series.csv", newline="") as f:
            wall = [r for r in csv.DictReader(f) if r.get("blast_gas_front_radius_m") not in (None, "")]
    except FileNotFoundError:
        wall = []
    for (key, _), radius in zip(BLAST, FRONT_RADII):
        hit = next((float(r["time_s"]) for r in wall if float(r["blast_gas_front_radius_m"]) >= radius), None)
        row[key] = hit if hit is not None else (NOT_REACHED if wall else None)
    row["blast_arrival_s"] = event_time(text, "blast gas reaches the rock's outer surface")
    m = re.search(r"summary at t = (\S+) s", text)
    row["end_s"] = float(m.group(1)) if m else None
    return row


def cell(x):
    return "" if x is None else x if isinstance(x, str) else f"{x:.10g}"


def number(x):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.4g}"


def statistics_line(label, values, runs):
    """A Markdown table row of the numbers among values; notes the runs that lack the quantity."""
    xs = [v for v in values if isinstance(v, float) and math.isfinite(v)]
    unreached = sum(v == NOT_REACHED for v in values)
    missing = runs - len(xs) - unreached
    notes = ([f"{unreached} not reached"] if unreached else []) + ([f"{missing} missing"] if missing else [])
    if not xs:
        return f"| {label} | 0 | - | - | - | - | - | {', '.join(notes)} |"
    mean = statistics.fmean(xs)
    std = statistics.stdev(xs) if len(xs) > 1 else float("nan")
    cv = f"{100 * std / abs(mean):.2f} %" if len(xs) > 1 and mean != 0 else "-"
    return (f"| {label} | {len(xs)} | {number(mean)} | {number(std)} | {number(min(xs))} | {number(max(xs))} | {cv} "
            f"| {', '.join(notes)} |")


def write_tables(args, out, failed):
    seeds = [k for k in range(1, args.n + 1) if (out / f"seed_{k}").is_dir()]
    if not seeds:
        print(f"realisations: no seed_K folders (K = 1..{args.n}) in {out}", file=sys.stderr)
        sys.exit(2)
    rows = {k: collect(out / f"seed_{k}") for k in seeds}
    columns = [q[0] for q in QUANTITIES] + [EJECTION[0]] + [b[0] for b in BLAST]
    with open(out / "realisations.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["seed", "directory"] + columns)
        for k, row in rows.items():
            w.writerow([k, f"seed_{k}"] + [cell(row[c]) for c in columns])
    lines = [f"# Realisations of {Path(args.case).name}: runs of seeds {', '.join(map(str, seeds))} in {out}",
             "", f"{'Gmsh mesh realisation K (--remesh); ' if args.remesh else ''}"
             f"mesh jitter {args.jitter} (this command's --jitter)"
             f"{'; each mesh turned by rock.mesh.rotation = rotation_deg(K) (--rotate)' if args.rotate else ''}; "
             f"overrides: {' '.join(args.overrides) or 'none'}.", "",
             "| quantity | runs | mean | std (n-1) | min | max | CV | notes |",
             "|---|---:|---:|---:|---:|---:|---:|---|"]
    for key, _, _, label in QUANTITIES + [(EJECTION[0], None, None, EJECTION[1])] + [(k, None, None, l) for k, l in BLAST]:
        lines.append(statistics_line(label, [row[key] for row in rows.values()], len(seeds)))
    if len(seeds) < args.n:
        absent = sorted(set(range(1, args.n + 1)) - set(seeds))
        lines += ["", f"No folder for seed(s) {', '.join(map(str, absent))}."]
    if failed:
        lines += ["", f"blastsim failed for seed(s) {', '.join(map(str, failed))} (see their blastsim.log): their rows "
                  "hold whatever their folders had."]
    text = "\n".join(lines) + "\n"
    (out / "realisations.md").write_text(text)
    print(text, end="")
    print(f"written: {out / 'realisations.csv'}, {out / 'realisations.md'}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case", help="case file (TOML)")
    p.add_argument("n", type=int, help="number of realisations (seeds 1..N)")
    p.add_argument("overrides", nargs="*", help="extra section.key=value overrides for every run")
    p.add_argument("--remesh", action="store_true",
                   help="a different Gmsh mesh per realisation: rock.mesh.realisation=K in realisation K")
    p.add_argument("--jitter", type=float, default=None,
                   help="rock.mesh.jitter of every run (default 0.03, or 0 with --remesh)")
    p.add_argument("--rotate", action="store_true",
                   help="also turn the mesh (disc shapes): rock.mesh.rotation=rotation_deg(K) in realisation K")
    p.add_argument("--strength-seed", action="store_true",
                   help="also draw the joint strengths afresh: rock.heterogeneity.seed=K in realisation K")
    p.add_argument("--out", help="folder of the runs (default realisations_<case stem>)")
    p.add_argument("--blastsim", help="the driver (default build-cpu/apps/blastsim/blastsim of this repository)")
    p.add_argument("--resume", action="store_true", help="skip seeds whose run already reached time.end")
    p.add_argument("--jobs", type=int, default=1,
                   help="runs at once (default 1); with more than one and OMP_NUM_THREADS unset, each run gets "
                        "OMP_NUM_THREADS = cores / jobs (at least 1)")
    p.add_argument("--collect-only", action="store_true", help="run nothing; rebuild the tables from the folders")
    args = p.parse_intermixed_args()
    if args.jitter is None:
        args.jitter = 0.0 if args.remesh else 0.03
    if not 1 <= args.n <= 10000:
        p.error(f"N = {args.n}: must be in 1..10000")
    if not 1 <= args.jobs <= 256:
        p.error(f"--jobs {args.jobs}: must be in 1..256")
    bad = [o for o in args.overrides if "=" not in o]
    if bad:
        p.error(f"overrides must read section.key=value: {' '.join(bad)}")
    out = Path(args.out or f"realisations_{Path(args.case).stem}")
    blastsim = check_arguments(args, p, out)
    failed = [] if args.collect_only else run_all(args, out, blastsim)
    write_tables(args, out, failed)
    if failed:
        sys.exit(f"realisations: seed(s) {', '.join(map(str, failed))} failed")


if __name__ == "__main__":
    main()
