#!/usr/bin/python3
"""Figure of the G11 shock tubes (tests/cip/test_two_materials.cpp): ANFO detonation products into air, blastsim's
profiles against the exact two-material Riemann solution.

Usage: BLASTSIM_FIGURE_DIR=DIR build-cpu/tests/cip/test_cip "G11 shock tubes*"
       scripts/plot-products-shock-tube.py DIR docs/figures/products_shock_tube.png
Needs Debian's python3-matplotlib (/usr/bin/python3).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    src, out = sys.argv[1], sys.argv[2]
    cases = [("1000", "products 400 kg/m3 at 1 GPa"), ("10000", "products 800 kg/m3 at 10 GPa")]
    fig, axes = plt.subplots(3, 2, figsize=(10, 9), sharex=True)
    for col, (tag, title) in enumerate(cases):
        d = read(f"{src}/products_shock_tube_{tag}MPa.csv")
        t_us = d["t_s"][0] * 1e6
        for row, (key, exact, label, scale) in enumerate(
            [("rho", "rho_exact", "density [kg/m3]", 1.0), ("p_Pa", "p_exact", "pressure [MPa]", 1e-6),
             ("u_m_per_s", "u_exact", "velocity [m/s]", 1.0)]):
            ax = axes[row][col]
            ax.plot(d["x_m"], [v * scale for v in d[exact]], "k-", lw=1.2, label="exact")
            ax.plot(d["x_m"], [v * scale for v in d[key]], "r.", ms=2, label="blastsim, 800 cells")
            if key != "u_m_per_s":
                ax.set_yscale("log")
            ax.set_ylabel(label)
            if row == 0:
                ax.set_title(f"ANFO {title} into air, t = {t_us:.1f} us")
                ax.legend()
        axes[2][col].set_xlabel("x [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
