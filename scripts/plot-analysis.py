#!/usr/bin/python3
"""Figures of the rock analysis of a blastsim run (fragments, size distribution, PPV, damage zone), drawn with
matplotlib from the run's rock VTK series (read with VTK's Python readers) and its analysis CSV files.

Usage: scripts/plot-analysis.py OUTPUT_DIR [--snapshot N]

N is the number of a rock snapshot (rock_NNNNNN.vtu, fragments_NNNNNN.csv); the default is the last one in
rock.pvd. Writes into OUTPUT_DIR (a figure whose input files are missing is skipped with a note):
  fragments.png          the rock's triangles where they are at snapshot N, one colour per fragment (tab20 cycled
                         over the labels in order; fines in light grey), broken joints in black
  size_distribution.png  mass passing against sieve size (log axis) at snapshot N with the Swebrec and
                         Rosin-Rammler fits (parameters from fragmentation_series.csv) and X50 / X80 marked; the
                         last snapshot reads size_distribution.csv, an earlier one rebuilds it from fragments_N.csv
  ppv_distance.png       peak particle velocity against distance from hole 0 (ppv.csv, log-log) with the
                         least-squares power law PPV = K d^-alpha
  probe_velocity.png     speed history of every rock probe (rock_probes.csv)
  damage_radii.png       crushed and cracked radius of every hole against time (fragmentation_series.csv)
Needs Debian's python3-matplotlib and python3-vtk9 (/usr/bin/python3).
"""
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blastsim_output import pvd_entries, read_csv, read_grid  # noqa: E402








def cell_array(grid, name):
    a = grid.GetCellData().GetArray(name)
    return None if a is None else vtk_to_numpy(a)


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(path)


def series_row(series, t):
    """The row of fragmentation_series.csv nearest to time t, as a dict (None without the file)."""
    if series is None:
        return None
    k = int(np.argmin(np.abs(series["time_s"] - t)))
    return {name: col[k] for name, col in series.items()}


def size_text(x):
    return f"{x:.3g} m" if x > 0 else "in the fines"


def fragments_figure(out, rock_file, joints_file, fragments, row, t):
    g = read_grid(os.path.join(out, rock_file))
    tris = vtk_to_numpy(g.GetPoints().GetData())[:, :2].reshape(-1, 3, 2)  # three own nodes per triangle
    ids = cell_array(g, "fragment_id")
    colours = np.tile(matplotlib.colors.to_rgba("C0"), (len(tris), 1))
    count = "?"
    if ids is not None:
        labels, rank = np.unique(ids, return_inverse=True)
        colours = plt.get_cmap("tab20")(rank % 20)
        count = len(labels)
        if fragments is not None:
            fine = np.asarray(fragments["label"])[np.asarray(fragments["fines"]) > 0]
            colours[np.isin(ids, fine)] = matplotlib.colors.to_rgba("0.85")
            count = len(fragments["label"])
    fig, ax = plt.subplots(figsize=(7, 6.4), constrained_layout=True)
    ax.add_collection(PolyCollection(tris, facecolors=colours, edgecolors="none"))
    if joints_file and os.path.exists(os.path.join(out, joints_file)):
        j = read_grid(os.path.join(out, joints_file))
        segments = vtk_to_numpy(j.GetPoints().GetData())[:, :2].reshape(-1, 2, 2)
        broken = cell_array(j, "broken")
        if broken is not None and broken.any():
            ax.add_collection(LineCollection(segments[broken.astype(bool)], colors="black", linewidths=0.4))
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    x50 = f", X50 {size_text(row['x50_m'])}" if row is not None else ""
    pieces = f"{count} fragment{'' if count == 1 else 's'}"
    ax.set_title(f"fragments at t = {t * 1e3:.3f} ms: {pieces}{x50}\n(fines light grey, broken joints black)")
    return fig


def swebrec(x, x50, xmax, b):
    """Swebrec passing, as libfdem's swebrec_passing."""
    with np.errstate(divide="ignore", invalid="ignore"):
        p = 1 / (1 + (np.log(xmax / x) / np.log(xmax / x50)) ** b)
    return np.where(x >= xmax, 1.0, p)


def rosin_rammler(x, x50, n):
    return 1 - np.exp(-math.log(2) * (x / x50) ** n)


def size_figure(out, data, row):
    """data: (sieve sizes, passing fractions); row: the fragmentation_series.csv row of the same snapshot."""
    size, passing = data
    fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
    ax.step(size, 100 * passing, where="post", color="0.4", lw=0.8)
    ax.plot(size, 100 * passing, "o", ms=4, color="k", label=f"fragments ({len(size)} sized)")
    lo, hi = size.min() / 2, size.max() * 2
    x = np.geomspace(lo, hi, 300)
    if row is not None:
        sw = (row["swebrec_x50_m"], row["swebrec_xmax_m"], row["swebrec_b"])
        if all(np.isfinite(v) and v > 0 for v in sw):
            ax.plot(x, 100 * swebrec(x, *sw), color="C0",
                    label=f"Swebrec: x50 {sw[0]:.3g} m, xmax {sw[1]:.3g} m, b {sw[2]:.3g} "
                          f"(R² {row['swebrec_r2']:.3f})")
        else:
            ax.plot([], [], " ", label="Swebrec: no fit (too few sized fragments)")
        rr = (row["rosin_rammler_x50_m"], row["rosin_rammler_n"])
        if all(np.isfinite(v) and v > 0 for v in rr):
            ax.plot(x, 100 * rosin_rammler(x, *rr), color="C1",
                    label=f"Rosin-Rammler: x50 {rr[0]:.3g} m, n {rr[1]:.3g} (R² {row['rosin_rammler_r2']:.3f})")
        else:
            ax.plot([], [], " ", label="Rosin-Rammler: no fit (too few sized fragments)")
        for key, p, c in (("x50_m", 50, "C2"), ("x80_m", 80, "C3")):
            if row[key] > 0:
                ax.axvline(row[key], color=c, ls=":", lw=1)
                ax.axhline(p, color=c, ls=":", lw=1)
                ax.plot(row[key], p, "s", color=c, label=f"X{p} = {row[key]:.3g} m")
        title = f"size distribution at t = {row['time_s'] * 1e3:.3f} ms"
    else:
        title = "size distribution"
    ax.set_xscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, 102)
    ax.set_xlabel("sieve size (minimum Feret width) [m]")
    ax.set_ylabel("mass passing [%]")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    return fig


def size_data(out, fragments, latest):
    """(sizes, passing) of the snapshot: size_distribution.csv for the latest one, else rebuilt from fragments."""
    if latest:
        d = read_csv(os.path.join(out, "size_distribution.csv"))
        if d is not None:
            return d["sieve_size_m"], d["passing"]
    if fragments is None:
        return None
    sized = np.asarray(fragments["fines"]) == 0
    mass = np.asarray(fragments["mass_kg_per_m"])
    order = np.argsort(fragments["sieve_size_m"][sized], kind="stable")
    passed = mass[~sized].sum() + np.cumsum(mass[sized][order])
    return fragments["sieve_size_m"][sized][order], passed / mass.sum()


def ppv_figure(ppv):
    d, v = ppv["distance_from_hole0_m"], ppv["ppv_m_per_s"]
    ok = np.isfinite(d) & np.isfinite(v) & (d > 0) & (v > 0)
    fig, ax = plt.subplots(figsize=(6.4, 4.8), constrained_layout=True)
    ax.loglog(d[ok], v[ok], "o", color="k", label="rock probes")
    for name, x, y in zip(np.asarray(ppv["name"])[ok], d[ok], v[ok]):
        ax.annotate(str(name), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if ok.sum() >= 2:
        slope, intercept = np.polyfit(np.log(d[ok]), np.log(v[ok]), 1)
        x = np.geomspace(d[ok].min(), d[ok].max(), 50)
        ax.loglog(x, np.exp(intercept) * x**slope, color="C1",
                  label=f"PPV = {np.exp(intercept):.3g} d^-{-slope:.3g}  (d in m, PPV in m/s)")
    ax.set_xlabel("distance from hole 0 [m]")
    ax.set_ylabel("peak particle velocity [m/s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def probes_figure(probes):
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    for key in (k for k in probes if k.endswith("_speed_m_per_s")):
        ax.plot(probes["time_s"] * 1e3, probes[key], label=key[: -len("_speed_m_per_s")])
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("particle speed [m/s]")
    ax.set_title("rock probes")
    ax.legend(fontsize=8)
    return fig


def radii_figure(series):
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    t = series["time_s"] * 1e3
    holes = sorted({int(m.group(1)) for k in series for m in [re.match(r"hole(\d+)_crushed_radius_m$", k)] if m})
    for h in holes:
        c = f"C{h % 10}"
        ax.plot(t, series[f"hole{h}_cracked_radius_m"], color=c, marker=".", label=f"hole {h}: cracked")
        ax.plot(t, series[f"hole{h}_crushed_radius_m"], color=c, ls="--", marker=".", label=f"hole {h}: crushed")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("radius from the hole centre [m]")
    ax.set_title("damage zone")
    ax.legend(fontsize=8)
    return fig


def main():
    if len(sys.argv) < 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    out = sys.argv[1]
    wanted = int(sys.argv[sys.argv.index("--snapshot") + 1]) if "--snapshot" in sys.argv else None
    rock = pvd_entries(os.path.join(out, "rock.pvd"))
    joints = dict((f.replace("joints_", "rock_"), f) for _, f in pvd_entries(os.path.join(out, "joints.pvd")))
    series = read_csv(os.path.join(out, "fragmentation_series.csv"))
    numbers = [int(re.search(r"(\d+)\.vtu$", f).group(1)) for _, f in rock]
    if rock:
        k = len(rock) - 1 if wanted is None else numbers.index(wanted) if wanted in numbers else None
        if k is None:
            sys.exit(f"plot-analysis: no rock snapshot {wanted} in {out}/rock.pvd (has {numbers[0]}..{numbers[-1]})")
        t, rock_file = rock[k]
        number, latest = numbers[k], k == len(rock) - 1
    elif series is not None:  # no VTK output: the analysis CSV files only
        if wanted is not None and wanted >= len(series["time_s"]):
            sys.exit(f"plot-analysis: no snapshot {wanted} in {out}/fragmentation_series.csv")
        number = len(series["time_s"]) - 1 if wanted is None else wanted
        t, rock_file, latest = series["time_s"][number], None, number == len(series["time_s"]) - 1
    else:
        sys.exit(f"plot-analysis: {out} has neither rock.pvd nor fragmentation_series.csv")
    fragments = read_csv(os.path.join(out, f"fragments_{number:06d}.csv"))
    row = series_row(series, t)
    if rock_file:
        save(fragments_figure(out, rock_file, joints.get(rock_file), fragments, row, t), out, "fragments.png")
    data = size_data(out, fragments, latest)
    if data is not None and len(data[0]) > 0:
        save(size_figure(out, data, row), out, "size_distribution.png")
    else:
        print("plot-analysis: no sized fragments: size_distribution.png skipped")
    ppv = read_csv(os.path.join(out, "ppv.csv"))
    if ppv is not None:
        save(ppv_figure(ppv), out, "ppv_distance.png")
    else:
        print("plot-analysis: no ppv.csv: ppv_distance.png skipped")
    probes = read_csv(os.path.join(out, "rock_probes.csv"))
    if probes is not None:
        save(probes_figure(probes), out, "probe_velocity.png")
    if series is not None:
        save(radii_figure(series), out, "damage_radii.png")


if __name__ == "__main__":
    main()
