#!/usr/bin/python3
"""Figures of a coupled single-hole run (examples/single_hole), drawn with matplotlib from the run's VTK
series (read with VTK's Python readers) and CSV series.

Usage: scripts/plot-single-hole.py OUTPUT_DIR [--fig4-time SECONDS]

Writes into OUTPUT_DIR:
  fig3_velocity_NNNNNN.png  gas velocity magnitude with the rock and its cracks, one per snapshot (paper Fig. 3)
  fig4_pressure_stress.png  gas pressure and the rock's most compressive principal stress near the hole at the
                            first snapshot at or after --fig4-time (default: the first after t = 0) (paper Fig. 4)
  hole_pressure.png         gas pressure at the blasthole centre (point_hole.csv)
  wall_pressure_stress.png  gas pressure at the hole wall against the rock's radial stress there (wall_series.csv)
  cracks.png                broken joints and total crack length
  gas_inside_rock.png       gas mass inside the rock's outer radius (coupling_series.csv, monitor region)
  energy_budget.png         the terms of the gas + rock energy budget and its residual
With crack gas ([crack_gas] enabled = true), also:
  fig3_crack_gas_NNNNNN.png the grid gas's pressure with the cracks coloured by their own gas's pressure
  crack_gas.png             gas mass in the cracks, their largest pressure and the hole-centre pressure, and
                            how far the blast gas has gone, in the grid and the cracks (blast_gas_front_radius_m)
Needs Debian's python3-matplotlib and python3-vtk9 (/usr/bin/python3).
"""
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
from blastsim_output import pvd_entries, read_cracks, read_csv, read_gas, read_grid, read_rock  # noqa: E402


def read_crack_gas(path):
    """Broken joints as segments with their gas pressure [Pa] (None without crack gas in the file)."""
    g = read_grid(path)
    p = g.GetCellData().GetArray("gas_pressure")
    if p is None:
        return None
    pts = vtk_to_numpy(g.GetPoints().GetData())[:, :2].reshape(-1, 2, 2)
    broken = vtk_to_numpy(g.GetCellData().GetArray("broken")).astype(bool)
    return pts[broken], vtk_to_numpy(p)[broken]


def save(fig, out, name):
    fig.savefig(os.path.join(out, name), dpi=110, bbox_inches="tight")
    plt.close(fig)


def fig3(out, gas_file, rock_file, joints_file, t):
    g = read_gas(os.path.join(out, gas_file))
    tris, _ = read_rock(os.path.join(out, rock_file))
    cracks = read_cracks(os.path.join(out, joints_file))
    fig, ax = plt.subplots(figsize=(6.4, 5.6), constrained_layout=True)
    speed = np.ma.masked_where(g["active"] == 0, g["speed"])
    im = ax.imshow(speed, origin="lower", extent=g["extent"], cmap="viridis")
    fig.colorbar(im, ax=ax, label="gas velocity magnitude [m/s]")
    ax.add_collection(PolyCollection(tris, facecolors="0.75", edgecolors="none", alpha=0.6))
    ax.add_collection(LineCollection(cracks, colors="red", linewidths=0.8))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"gas speed, rock (grey) and cracks (red) at t = {t * 1e3:.3f} ms")
    return fig


def fig3_crack_gas(out, gas_file, rock_file, cracks, t):
    """The grid gas's pressure, the rock, and the cracks coloured by their own gas's pressure (one scale)."""
    g = read_gas(os.path.join(out, gas_file))
    tris, _ = read_rock(os.path.join(out, rock_file))
    segs, p = cracks
    fig, ax = plt.subplots(figsize=(6.4, 5.6), constrained_layout=True)
    vmax = max(np.max(np.where(g["active"] == 1, g["pressure"], 0)), np.max(p, initial=0)) / 1e6
    norm = matplotlib.colors.Normalize(vmin=0, vmax=vmax)
    im = ax.imshow(np.ma.masked_where(g["active"] == 0, g["pressure"] / 1e6), origin="lower", extent=g["extent"],
                   cmap="inferno", norm=norm)
    fig.colorbar(im, ax=ax, label="gas pressure [MPa] (grid and cracks)")
    ax.add_collection(PolyCollection(tris, facecolors="0.8", edgecolors="none", alpha=0.7))
    lines = LineCollection(segs, cmap="inferno", norm=norm, linewidths=1.6)
    lines.set_array(p / 1e6)
    ax.add_collection(lines)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"gas pressure in the grid and in the cracks at t = {t * 1e3:.3f} ms")
    return fig


def fig4(out, gas_file, rock_file, t, zoom):
    g = read_gas(os.path.join(out, gas_file))
    tris, smin = read_rock(os.path.join(out, rock_file))
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    p = np.ma.masked_where(g["active"] == 0, g["pressure"]) / 1e6
    im = a.imshow(p, origin="lower", extent=g["extent"], cmap="inferno")
    fig.colorbar(im, ax=a, label="gas pressure [MPa]")
    pc = PolyCollection(tris, array=smin / 1e6, cmap="coolwarm", edgecolors="none")
    b.add_collection(pc)
    fig.colorbar(pc, ax=b, label="rock minimum principal stress [MPa] (compression < 0)")
    for ax, title in ((a, "gas pressure"), (b, "rock PS3 (most compressive)")):
        ax.set_xlim(-zoom, zoom)
        ax.set_ylim(-zoom, zoom)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(f"{title}, t = {t * 1e6:.1f} us")
    return fig


def outer_radius(out):
    """The rock's outer radius [m] as summary.txt states it (the blasthole monitor's), or None."""
    try:
        with open(os.path.join(out, "summary.txt")) as f:
            m = re.search(r"outer\s+radius \(([0-9.eE+-]+) m\)", f.read())
        return float(m.group(1)) if m else None
    except (OSError, ValueError):
        return None


def series_plots(out):
    hole = read_csv(os.path.join(out, "point_hole.csv"))
    if hole is not None:
        fig, ax = plt.subplots()
        ax.plot(hole["t"] * 1e3, hole["p"] / 1e6)
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("gas pressure at the hole centre [MPa]")
        save(fig, out, "hole_pressure.png")
    wall = read_csv(os.path.join(out, "wall_series.csv"))
    if wall is not None:
        fig, ax = plt.subplots()
        t = wall["time_s"] * 1e6
        ax.plot(t, wall["gas_pressure_wall_mean_Pa"] / 1e6, label="gas pressure at the wall (mean of 64 points)")
        ax.plot(t, -wall["rock_radial_stress_wall_mean_Pa"] / 1e6, label="rock radial stress at the wall (-sigma_rr, mean)")
        ax.set_xlabel("time [us]")
        ax.set_ylabel("[MPa]")
        ax.legend()
        save(fig, out, "wall_pressure_stress.png")
    cs = read_csv(os.path.join(out, "coupling_series.csv"))
    if cs is None:
        return
    if "crack_gas_mass_kg_per_m" in cs and np.any(cs["crack_gas_mass_kg_per_m"] > 0):
        front = wall is not None and "blast_gas_front_radius_m" in wall
        fig, ax = plt.subplots(3 if front else 2, 1, figsize=(6.4, 8.8 if front else 6.4), sharex=True,
                               constrained_layout=True)
        t = cs["time_s"] * 1e3
        ax[0].plot(t, cs["crack_gas_mass_kg_per_m"] * 1e3)
        ax[0].set_ylabel("gas mass in the cracks [g/m]")
        ax[1].plot(t, cs["crack_gas_pressure_max_Pa"] / 1e6, label="largest crack gas pressure")
        if hole is not None:
            ax[1].plot(hole["t"] * 1e3, hole["p"] / 1e6, label="gas pressure at the hole centre")
        ax[1].set_ylabel("[MPa]")
        ax[1].set_yscale("log")  # a crack pressed shut on its gas can spike by orders of magnitude
        ax[1].legend()
        if front:  # how far the blast gas has gone, through the grid and the cracks (wall_series.csv)
            ax[2].plot(wall["time_s"] * 1e3, wall["blast_gas_front_radius_m"], label="blast gas front (grid and cracks)")
            ax[2].plot(wall["time_s"] * 1e3, wall["blast_gas_front_crack_radius_m"], ls=":", label="in the cracks' own gas")
            outer = outer_radius(out)
            if outer is not None:
                ax[2].axhline(outer, color="grey", lw=0.8, ls="--", label="the rock's outer surface")
            ax[2].set_ylabel("distance from the hole centre [m]")
            ax[2].legend()
        ax[-1].set_xlabel("time [ms]")
        save(fig, out, "crack_gas.png")
    t = cs["time_s"] * 1e3
    fig, ax = plt.subplots()
    ax.plot(t, cs["broken_joints"], label="broken joints")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("broken joints")
    ax2 = ax.twinx()
    ax2.plot(t, cs["crack_length_m"], color="C1", label="crack length")
    ax2.set_ylabel("total crack length [m]", color="C1")
    save(fig, out, "cracks.png")
    mass = [k for k in cs if k.endswith("_mass_kg_per_m") and k != "gas_mass_kg_per_m"]
    if mass:
        fig, ax = plt.subplots()
        for k in mass:
            ax.plot(t, cs[k], label=k.replace("_mass_kg_per_m", ""))
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("gas mass [kg/m]")
        ax.legend()
        save(fig, out, "gas_inside_rock.png")
    fig, ax = plt.subplots()
    for key, label in (("gas_work_on_rock_J_per_m", "work of the gas on the rock"),
                       ("rock_kinetic_J_per_m", "rock kinetic"), ("rock_strain_J_per_m", "rock strain"),
                       ("fracture_dissipated_J_per_m", "fracture"), ("contact_work_J_per_m", "contact + friction"),
                       ("gas_energy_out_J_per_m", "gas energy out of the grid"),
                       ("immersed_face_work_J_per_m", "work of the moving immersed faces on the gas"),
                       ("budget_residual_J_per_m", "budget residual")):
        if key in cs:
            ax.plot(t, cs[key] / 1e3, label=label)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("[kJ/m]")
    ax.legend(fontsize=8)
    save(fig, out, "energy_budget.png")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    fig4_time = float(sys.argv[sys.argv.index("--fig4-time") + 1]) if "--fig4-time" in sys.argv else None
    gas, rock, joints = (pvd_entries(os.path.join(out, f)) for f in ("gas.pvd", "rock.pvd", "joints.pvd"))
    n = min(len(gas), len(rock), len(joints))
    for k in range(n):
        save(fig3(out, gas[k][1], rock[k][1], joints[k][1], gas[k][0]), out, f"fig3_velocity_{k:06d}.png")
        cracks = read_crack_gas(os.path.join(out, joints[k][1]))
        if cracks is not None:
            save(fig3_crack_gas(out, gas[k][1], rock[k][1], cracks, gas[k][0]), out, f"fig3_crack_gas_{k:06d}.png")
    later = [k for k in range(n) if (gas[k][0] > 0 if fig4_time is None else gas[k][0] >= fig4_time)]
    if later:
        k = later[0]
        tris, _ = read_rock(os.path.join(out, rock[k][1]))
        hole = np.min(np.hypot(tris[..., 0], tris[..., 1]))
        save(fig4(out, gas[k][1], rock[k][1], gas[k][0], 4 * hole), out, "fig4_pressure_stress.png")
    series_plots(out)
    print(f"plot-single-hole: figures written to {out}")


if __name__ == "__main__":
    main()
