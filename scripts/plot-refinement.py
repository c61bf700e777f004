#!/usr/bin/python3
"""Plot a refinement study: the mean and standard deviation (n-1) of each level's realisations against the level's size.

Usage: scripts/plot-refinement.py --level LABEL:X:DIR [--level ...] [--xlabel TEXT] [--title TEXT] OUT.png

Each level is one folder written by scripts/realisations.py (its realisations.csv); X is the number to plot it at
(e.g. the triangle size in mm) and LABEL its name on the plot. Two panels: the crack length, and the blast gas's
front at 0.2 / 0.4 / 0.6 m and its arrival at the outer surface (runs that did not reach one are left out of that
one's mean). Needs Python 3 with matplotlib (/usr/bin/python3 on Debian: python3-matplotlib).
"""
import argparse
import csv
import statistics
import sys
from pathlib import Path

TIMES = [("blast_front_20cm_s", "front at 0.2 m"), ("blast_front_40cm_s", "front at 0.4 m"),
         ("blast_front_60cm_s", "front at 0.6 m"), ("blast_arrival_s", "at the outer surface")]


def level_stats(folder, key):
    """(mean, standard deviation, runs) of one column of folder/realisations.csv over the runs that have a number."""
    with open(Path(folder) / "realisations.csv", newline="") as f:
        values = []
        for row in csv.DictReader(f):
            try:
                values.append(float(row[key]))
            except (KeyError, TypeError, ValueError):  # "not reached" or missing
                pass
    if not values:
        return None
    return statistics.mean(values), statistics.stdev(values) if len(values) > 1 else 0.0, len(values)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", help="the figure (PNG)")
    p.add_argument("--level", action="append", required=True, help="LABEL:X:DIR, one per level")
    p.add_argument("--xlabel", default="element size [mm]")
    p.add_argument("--title", default="")
    args = p.parse_args()
    levels = []
    for spec in args.level:
        parts = spec.split(":", 2)
        if len(parts) != 3:
            p.error(f"--level {spec}: give LABEL:X:DIR")
        try:
            x = float(parts[1])
        except ValueError:
            p.error(f"--level {spec}: X = {parts[1]} is not a number")
        if not (Path(parts[2]) / "realisations.csv").exists():
            p.error(f"--level {spec}: no realisations.csv in {parts[2]} (run scripts/realisations.py there first)")
        levels.append((parts[0], x, parts[2]))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    xs = [x for _, x, _ in levels]
    crack = [level_stats(d, "crack_length_m") for _, _, d in levels]
    ax1.errorbar([x for x, c in zip(xs, crack) if c], [c[0] for c in crack if c], yerr=[c[1] for c in crack if c],
                 marker="o", capsize=4)
    for (label, x, _), c in zip(levels, crack):
        if c:
            ax1.annotate(f"{label} (n={c[2]})", (x, c[0]), textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax1.set_xlabel(args.xlabel)
    ax1.set_ylabel("crack length [m]")
    ax1.grid(True, alpha=0.3)
    for key, name in TIMES:
        st = [level_stats(d, key) for _, _, d in levels]
        pts = [(x, s) for x, s in zip(xs, st) if s]
        if pts:
            ax2.errorbar([x for x, _ in pts], [1e3 * s[0] for _, s in pts], yerr=[1e3 * s[1] for _, s in pts],
                         marker="o", capsize=4, label=name)
    ax2.set_xlabel(args.xlabel)
    ax2.set_ylabel("blast gas arrival [ms]")
    ax2.legend(fontsize=8)
    ax2.grid(True, alpha=0.3)
    for ax in (ax1, ax2):
        ax.invert_xaxis()  # finer to the right
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"written: {args.out}")


if __name__ == "__main__":
    sys.exit(main())
