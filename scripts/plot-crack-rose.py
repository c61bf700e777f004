#!/usr/bin/python3
"""Crack roses of scripts/stress-blast-study.sh: for each stress ratio, the crack length in each 30-degree sector of
direction from the hole (crack_rose.csv), the mean over the seeds as bars and each seed as a line.

Usage: scripts/plot-crack-rose.py STUDY_DIR OUT.png
Needs Debian's python3-matplotlib (/usr/bin/python3).
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rose(path):
    rows = [r for r in csv.DictReader(open(path)) if r["hole"] == "0"]
    return [float(r["crack_length_m"]) for r in rows]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    study, out = sys.argv[1], sys.argv[2]
    ratios, seeds = (1, 2, 4), (1, 2, 3)
    fig, axes = plt.subplots(1, 3, subplot_kw={"projection": "polar"}, figsize=(12, 4.4))
    width = 2 * math.pi / 12
    centres = [width * (k + 0.5) for k in range(12)]
    top = 0.0
    roses = {}
    for ratio in ratios:
        roses[ratio] = [rose(f"{study}/ratio{ratio}_seed{s}/crack_rose.csv") for s in seeds]
        top = max(top, max(max(r) for r in roses[ratio]))
    for ax, ratio in zip(axes, ratios):
        mean = [sum(r[k] for r in roses[ratio]) / len(seeds) for k in range(12)]
        ax.bar(centres, mean, width=width, color="#d62728", alpha=0.45, edgecolor="k", label="mean of 3 seeds")
        for s, r in zip(seeds, roses[ratio]):
            ax.plot(centres + centres[:1], r + r[:1], lw=1, label=f"seed {s}")
        ax.set_ylim(0, 1.05 * top)
        ax.set_title(f"sigma_1 / sigma_3 = {ratio} (sigma_1 along x)", fontsize=10)
        ax.set_xticks([math.radians(a) for a in range(0, 360, 30)])
    axes[0].legend(loc="lower left", bbox_to_anchor=(-0.25, -0.2), fontsize=8)
    fig.suptitle("Crack length [m] by direction from the hole, 30-degree sectors (single-hole blast at 1.2 ms)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
