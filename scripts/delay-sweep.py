#!/usr/bin/python3
"""Delay sweep of two holes: run examples/bench_blast/two_holes.toml for several delays between its holes and
plot the crack length and X50 against the delay.

Usage: scripts/delay-sweep.py [--delays US,US,...] [--after US | --end US] [--out DIR] [--blastsim PATH]
                              [--collect-only] [section.key=value ...]

For each delay d (microseconds; default 0,10,22.5,45,90: simultaneous, shorter than, equal to, twice and four
times the P wave's travel time S / c_p = 22.5 us between the holes) it runs, one after another,
    blastsim -q two_holes.toml charge.1.initiation_time=d time.end=d+AFTER output.vtk=false
             output.directory=DIR/delay_<d>us [section.key=value ...]
(AFTER = 150 us: every run ends the same time after its second hole fired; with --end every run ends at that
time instead, the same time after its first hole, so that the delay is compared at equal time). From each run
it takes the crack
length and broken joints (last row of rock_series.csv) and the fragments, X50, X80 and fines (last row of
fragmentation_series.csv), and writes
  DIR/delay_sweep.csv  one row per delay
  DIR/delay_sweep.md   the same as a table (printed too)
  DIR/delay_sweep.png  crack length and X50 against the delay
--collect-only runs nothing and rebuilds the table and plot from the folders there. Needs /usr/bin/python3 with
matplotlib for the plot (the table needs Python only).
"""
import argparse
import csv
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from realisations import last_row  # noqa: E402  (the last row of a CSV file as a dict)

REPO = Path(__file__).resolve().parent.parent
CASE = REPO / "examples" / "bench_blast" / "two_holes.toml"
COLUMNS = [("crack_length_m", "rock_series.csv"), ("broken_joints", "rock_series.csv"),
           ("fragments", "fragmentation_series.csv"), ("x50_m", "fragmentation_series.csv"),
           ("x80_m", "fragmentation_series.csv"), ("fines_mass_fraction", "fragmentation_series.csv")]


def folder(out, delay_us):
    return out / f"delay_{delay_us:g}us"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--delays", default="0,10,22.5,45,90", help="delays in microseconds, comma-separated")
    p.add_argument("--after", type=float, default=150.0, help="run time after the second hole fires [us]")
    p.add_argument("--end", type=float, help="end every run at this time [us] instead (the same time for all)")
    p.add_argument("--out", type=Path, default=Path("delay_sweep"))
    p.add_argument("--blastsim", type=Path, default=REPO / "build-cpu" / "apps" / "blastsim" / "blastsim")
    p.add_argument("--collect-only", action="store_true")
    p.add_argument("overrides", nargs="*")
    a = p.parse_args()
    delays = [float(d) for d in a.delays.split(",")]
    a.out.mkdir(parents=True, exist_ok=True)
    if not a.collect_only:
        for d in delays:
            run = folder(a.out, d)
            cmd = [str(a.blastsim), "-q", str(CASE), f"charge.1.initiation_time={d * 1e-6:.9g}",
                   f"time.end={(a.end if a.end else d + a.after) * 1e-6:.9g}", "output.vtk=false",
                   f'output.directory="{run}"'] + a.overrides
            start = time.time()
            run.mkdir(parents=True, exist_ok=True)
            with open(run / "blastsim.log", "w") as log:
                rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
            print(f"delay {d:g} us: exit {rc} after {time.time() - start:.0f} s ({run})", flush=True)
    rows = []
    for d in delays:
        run = folder(a.out, d)
        row = {"delay_us": d}
        for col, src in COLUMNS:
            row[col] = last_row(run / src).get(col, "")
        rows.append(row)
    with open(a.out / "delay_sweep.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| delay [us] | delay / (S / c_p) | crack length [m] | broken joints | fragments | X50 [m] | X80 [m] | fines |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        def num(key, fmt):
            return fmt.format(float(r[key])) if r[key] != "" else "-"
        lines.append(f"| {r['delay_us']:g} | {r['delay_us'] / 22.5:.2f} | {num('crack_length_m', '{:.3f}')} | "
                     f"{num('broken_joints', '{:.0f}')} | {num('fragments', '{:.0f}')} | {num('x50_m', '{:.4f}')} | "
                     f"{num('x80_m', '{:.4f}')} | {num('fines_mass_fraction', '{:.3f}')} |")
    (a.out / "delay_sweep.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: table only", file=sys.stderr)
        return
    done = [r for r in rows if r["crack_length_m"] != "" and r["x50_m"] != ""]
    if not done:
        return
    x = [r["delay_us"] for r in done]
    fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
    ax.plot(x, [float(r["crack_length_m"]) for r in done], "o-", color="C3")
    ax.set_xlabel("delay between the holes [us] (S / c_p = 22.5 us)")
    ax.set_ylabel("crack length [m]", color="C3")
    ax2 = ax.twinx()
    ax2.plot(x, [1e3 * float(r["x50_m"]) for r in done], "s--", color="C0")
    ax2.set_ylabel("X50 [mm]", color="C0")
    ax.axvline(22.5, color="0.6", lw=0.8, ls=":")
    ax.set_title(f"two holes at {a.end:g} us" if a.end else f"two holes, {a.after:g} us after the second fired")
    fig.savefig(a.out / "delay_sweep.png", dpi=110)


if __name__ == "__main__":
    main()
