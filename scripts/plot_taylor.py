#!/usr/bin/python3
"""Draws a Taylor impact result: the deformed rod (particles at their radius and height, coloured by
plastic strain) over the initial outline, with the digitised experimental profile if one is given.

  scripts/plot_taylor.py OUTPUT_DIR [--png taylor.png] [--experiment r_mm,z_mm;...] [--title TEXT]

OUTPUT_DIR is a burst output folder of options/scenes/taylor.opts (taylor_particles.csv,
taylor_profile.csv, summary.json)."""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--png", default=None)
    p.add_argument("--experiment", default=None, help="digitised profile 'r,z;r,z;...' in mm, z above the anvil")
    p.add_argument("--title", default=None)
    a = p.parse_args()
    with open(os.path.join(a.out, "summary.json")) as f:
        t = json.load(f)["taylor"]
    d = np.genfromtxt(os.path.join(a.out, "taylor_particles.csv"), delimiter=",", names=True)
    prof = np.genfromtxt(os.path.join(a.out, "taylor_profile.csv"), delimiter=",", names=True)
    L0, R0 = 1e3 * t["length0"], 0.5e3 * t["diameter0"]
    fig, ax = plt.subplots(figsize=(4.2, 6.5))
    sc = ax.scatter(1e3 * d["r_m"], 1e3 * d["z_m"], c=d["plastic_strain"], s=4, cmap="viridis", vmin=0)
    ax.plot(1e3 * prof["r_surface_m"], 1e3 * prof["z_m"], "k-", lw=0.8, label="profile (centres + half-size)")
    ax.plot([0, R0, R0, 0], [0, 0, L0, L0], "k--", lw=0.8, label="initial outline")
    if a.experiment:
        pts = np.array([[float(v) for v in s.split(",")] for s in a.experiment.split(";")])
        ax.plot(pts[:, 0], pts[:, 1], "ro", ms=3, label="experiment")
    ax.set_xlabel("radius (mm)")
    ax.set_ylabel("height above the anvil (mm)")
    ax.set_aspect("equal")
    ax.set_xlim(0, max(1.1 * 1e3 * d["r_m"].max(), 1.2 * R0))
    fig.colorbar(sc, ax=ax, label="plastic strain")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(a.title or f"{t['material']} {t['velocity']:g} m/s: Lf/L0 {t['Lf_centres'] / t['length0']:.3f}, Df/D0 {t['Df_centres'] / t['diameter0']:.3f}", fontsize=8)
    fig.tight_layout()
    png = a.png or os.path.join(a.out, "taylor.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
