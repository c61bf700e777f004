#!/usr/bin/python3
"""Figures of a run with charges (examples/bench_blast, or any case with [[charge]]), drawn with matplotlib from the
run's VTK series and CSV series.

Usage: scripts/plot-bench.py OUTPUT_DIR [--snapshots N]

Writes into OUTPUT_DIR:
  bench_snapshots.png   gas pressure (log scale) with the rock (grey) and its cracks (red) at N snapshots
                        spread over the run (default 4), the charges' holes marked
  hole_pressures.png    the borehole pressure of every charge against time (charges.csv), initiations marked
  bench_cracks.png      crack length and broken joints against time (rock_series.csv), initiations marked
Needs Debian's python3-matplotlib and python3-vtk9 (/usr/bin/python3).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blastsim_output import pvd_entries, read_cracks, read_csv, read_gas, read_rock  # noqa: E402


def charge_columns(charges):
    """Indices k of the charges in charges.csv."""
    k = 0
    while charges is not None and f"charge{k}_pressure_Pa" in charges:
        k += 1
    return range(k)


def initiations(charges):
    """Per charge the first time its released energy is positive (its initiation as the run saw it)."""
    out = []
    for k in charge_columns(charges):
        e = charges[f"charge{k}_energy_J_per_m"]
        fired = np.nonzero(e > 0)[0]
        out.append(charges["time_s"][fired[0]] if len(fired) else None)
    return out


def mark_initiations(ax, fired):
    for k, t in enumerate(fired):
        if t is not None:
            ax.axvline(t * 1e6, color="0.6", lw=0.8, ls="--")
            ax.text(t * 1e6, ax.get_ylim()[1], f" {k}", va="top", fontsize=8, color="0.4")


def snapshots(out, n):
    gas = pvd_entries(os.path.join(out, "gas.pvd"))
    rock = dict(pvd_entries(os.path.join(out, "rock.pvd")))
    joints = dict(pvd_entries(os.path.join(out, "joints.pvd")))
    if not gas:
        print("no gas.pvd (output.vtk = false?): no snapshot figure")
        return
    picks = sorted({int(round(x)) for x in np.linspace(0, len(gas) - 1, min(n, len(gas)))})
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.0), constrained_layout=True, squeeze=False)
    norm = matplotlib.colors.LogNorm(vmin=1e5, vmax=2e9)
    for ax, i in zip(axes[0], picks):
        t, gas_file = gas[i]
        g = read_gas(os.path.join(out, gas_file))
        im = ax.imshow(np.ma.masked_where(g["active"] == 0, np.clip(g["pressure"], 1e5, None)), origin="lower",
                       extent=g["extent"], cmap="inferno", norm=norm)
        if t in rock:
            tris, _ = read_rock(os.path.join(out, rock[t]))
            ax.add_collection(PolyCollection(tris, facecolors="0.8", edgecolors="none", alpha=0.8))
        if t in joints:
            ax.add_collection(LineCollection(read_cracks(os.path.join(out, joints[t])), colors="red", linewidths=0.5))
        ax.set_aspect("equal")
        ax.set_xlim(g["extent"][0], g["extent"][1])
        ax.set_ylim(g["extent"][2], g["extent"][3])
        ax.set_title(f"t = {t * 1e6:.0f} us")
        ax.set_xlabel("x [m]")
    axes[0][0].set_ylabel("y [m]")
    fig.colorbar(im, ax=axes[0].tolist(), label="gas pressure [Pa]", shrink=0.8)
    fig.savefig(os.path.join(out, "bench_snapshots.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)


def series(out):
    charges = read_csv(os.path.join(out, "charges.csv"))
    fired = initiations(charges)
    if charges is not None:
        fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
        for k in charge_columns(charges):
            ax.semilogy(charges["time_s"] * 1e6, charges[f"charge{k}_pressure_Pa"], label=f"charge {k}")
        ax.set_xlabel("t [us]")
        ax.set_ylabel("borehole pressure [Pa]")
        ax.legend()
        mark_initiations(ax, fired)
        fig.savefig(os.path.join(out, "hole_pressures.png"), dpi=110, bbox_inches="tight")
        plt.close(fig)
    rock = read_csv(os.path.join(out, "rock_series.csv"))
    if rock is not None:
        fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
        ax.plot(rock["time_s"] * 1e6, rock["crack_length_m"], color="C3")
        ax.set_xlabel("t [us]")
        ax.set_ylabel("crack length [m]", color="C3")
        ax2 = ax.twinx()
        ax2.plot(rock["time_s"] * 1e6, rock["broken_joints"], color="C0", lw=0.8)
        ax2.set_ylabel("broken joints", color="C0")
        mark_initiations(ax, fired)
        fig.savefig(os.path.join(out, "bench_cracks.png"), dpi=110, bbox_inches="tight")
        plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out", help="the run's output folder")
    p.add_argument("--snapshots", type=int, default=4, help="snapshots in bench_snapshots.png")
    a = p.parse_args()
    snapshots(a.out, a.snapshots)
    series(a.out)


if __name__ == "__main__":
    main()
