#!/usr/bin/env python3
"""Plots a gas run's CSV output with matplotlib: line-probe profiles and the conservation monitor.

Usage: scripts/plot-gas-results.py OUTPUT_DIR     (writes line_profiles.png and conservation.png there)
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def save(fig, axes, out_dir, name):
    """Grids every panel, lays the figure out and writes OUT_DIR/NAME; returns the path."""
    for a in axes:
        a.grid(alpha=0.3)
    fig.tight_layout()
    target = os.path.join(out_dir, name)
    fig.savefig(target, dpi=120)
    return target


def plot_lines(out_dir):
    files = sorted(glob.glob(os.path.join(out_dir, "line_*.csv")))
    if not files:
        return None
    fig, axes = plt.subplots(3, 1, figsize=(7, 9), sharex=True)
    for path in files:
        d = read_csv(path)
        if not d:
            continue
        x0, y0 = d["x"][0], d["y"][0]
        s = [((x - x0) ** 2 + (y - y0) ** 2) ** 0.5 for x, y in zip(d["x"], d["y"])]
        label = os.path.basename(path)[5:-4]
        speed = [(u * u + v * v) ** 0.5 for u, v in zip(d["u"], d["v"])]
        axes[0].plot(s, [p / 1e6 for p in d["p"]], label=label)
        axes[1].plot(s, d["rho"], label=label)
        axes[2].plot(s, speed, label=label)
    axes[0].set_ylabel("pressure [MPa]")
    axes[1].set_ylabel("density [kg/m3]")
    axes[2].set_ylabel("speed [m/s]")
    axes[2].set_xlabel("distance along the probe line [m]")
    axes[0].legend(fontsize=7, ncol=2)
    return save(fig, axes, out_dir, "line_profiles.png")


def plot_monitor(out_dir):
    path = os.path.join(out_dir, "gas_totals.csv")
    if not os.path.exists(path):
        return None
    d = read_csv(path)
    t = [v * 1e3 for v in d["time_s"]]
    e0, m0 = d["total_energy_J_per_m"][0], d["mass_kg_per_m"][0]
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    axes[0].plot(t, [v / e0 for v in d["internal_energy_J_per_m"]], label="internal")
    axes[0].plot(t, [v / e0 for v in d["kinetic_energy_J_per_m"]], label="kinetic")
    axes[0].plot(t, [v / e0 for v in d["energy_out_J_per_m"]], label="left the domain")
    axes[0].plot(t, [v / m0 for v in d["mass_out_kg_per_m"]], "--", label="mass left (of initial mass)")
    axes[0].set_ylabel("fraction of the initial energy")
    axes[0].legend(fontsize=8)
    axes[1].plot(t, d["mass_balance_drift"], label="mass balance")
    axes[1].plot(t, d["energy_balance_drift"], label="energy balance")
    axes[1].set_ylabel("relative drift")
    axes[1].set_xlabel("time [ms]")
    axes[1].legend(fontsize=8)
    return save(fig, axes, out_dir, "conservation.png")


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: plot-gas-results.py OUTPUT_DIR")
    for made in (plot_lines(sys.argv[1]), plot_monitor(sys.argv[1])):
        if made:
            print("wrote", made)


if __name__ == "__main__":
    main()
