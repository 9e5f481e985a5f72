#!/usr/bin/python3
"""Pictures of a run in phases (the container in a fire, options/scenes/pool_fire2d.opts).

    /usr/bin/python3 scripts/plot_fire.py OUTPUT_DIR [--png fire.png]

Writes OUTPUT_DIR/fire.png, four panels:
  1. the heat-up's end: the gas temperature (the gases' mass-weighted mean) with the particles
     coloured by their temperature (the last output at or before the heat_only switch);
  2. the temperature histories of each solid, hottest particle and mass-weighted mean, against time
     (monitor.csv's temperature_max_<material> and temperature_mean_<material>), with the switches;
  3. the last output: the gas pressure with the particles (intact steel by fragment, failed grey,
     the charge light);
  4. after ignition: the largest cell pressure and the wall's mean radial velocity (-grady) against
     the time since the mechanics began.
In 3-D (options/scenes/pool_fire3d.opts) panels 1 and 3 show the mid-length plane z = 0: the gas
cells of the first layer and the particles within one cell of it.
Needs numpy, h5py and matplotlib: use Debian's /usr/bin/python3.
"""
import argparse
import csv
import glob
import json
import os
import re

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def outputs(out, prefix):
    files = glob.glob(os.path.join(out, f"{prefix}_*.h5"))
    return sorted(files, key=lambda f: int(re.search(r"_(\d+)\.h5$", f).group(1)))


def output_time(path):
    with h5py.File(path, "r") as f:
        for key in ("time", "/time"):
            if key in f.attrs:
                return float(f.attrs[key])
    return None


def step_of(path):
    return int(re.search(r"_(\d+)\.h5$", path).group(1))


def gas_fields(path):
    with h5py.File(path, "r") as f:
        cells = f["cells"]
        names = sorted({k[: -len("_density")] for k in cells if k.endswith("_density")})
        gases = [n for n in names if f"{n}_temperature" in cells and n not in ("steel", "pbx")]
        rho = {n: cells[f"{n}_density"][0] for n in gases}
        T = {n: cells[f"{n}_temperature"][0] for n in gases}
        mass = sum(rho.values())
        Tgas = sum(rho[n] * T[n] for n in gases) / np.maximum(mass, 1e-300)
        return Tgas, cells["pressure"][0]


def particles(path, z_max=None):
    """The particles; in 3-D (z_max given) those with z < z_max only."""
    with h5py.File(path, "r") as f:
        g = f["particles"]
        d = {k: g[k][...] for k in ("coordinates", "temperature", "material", "fragment")}
        d["failed"] = g["failed"][...] if "failed" in g else np.zeros(len(d["material"]))
    if z_max is not None and d["coordinates"].shape[1] == 3:
        keep = d["coordinates"][:, 2] < z_max
        d = {k: v[keep] for k, v in d.items()}
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--png", default="fire.png")
    args = ap.parse_args()
    with open(os.path.join(args.out, "summary.json")) as f:
        summary = json.load(f)
    phases = summary.get("phases", {})
    lower = summary.get("grid_lower")
    # 3-D: the plane z = 0 (the first gas layer; the particles within one cell of it)
    z_max = None
    if summary.get("dim", 2) == 3:
        z_max = (summary["grid_upper"][2] - summary["grid_lower"][2]) / summary["cells"][2]
    with open(os.path.join(args.out, "monitor.csv")) as f:
        rows = list(csv.DictReader(f))
    time = np.array([float(r["time"]) for r in rows])
    steps = np.array([int(r["step"]) for r in rows])
    switch_heat_only = phases.get("heat_only_start", -1)
    switch_mech = phases.get("mechanics_start", -1)

    gas_files, part_files = outputs(args.out, "gas"), outputs(args.out, "particles")
    # the output closest before the heat-up's end, by step (monitor rows give each step's time)
    step_time = dict(zip(steps, time))
    def before(files, t):
        chosen = files[0]
        for fpath in files:
            s = step_of(fpath)
            if s in step_time and step_time[s] <= t * (1 + 1e-12):
                chosen = fpath
        return chosen

    fig, ax = plt.subplots(1, 4, figsize=(17, 6), gridspec_kw={"width_ratios": [1, 1.6, 1, 1.6]})
    # 1. heat-up
    g_heat = before(gas_files, switch_heat_only if switch_heat_only > 0 else time[-1])
    p_heat = before(part_files, switch_heat_only if switch_heat_only > 0 else time[-1])
    Tgas, _ = gas_fields(g_heat)
    ny, nx = Tgas.shape
    x0, y0 = (lower or [0, -0.1])[:2]
    p = particles(p_heat, z_max)
    xs = p["coordinates"][:, 0]
    ys = p["coordinates"][:, 1]
    # the cell size from the domain in the summary, else from the particles' extent
    upper = summary.get("grid_upper")
    if upper:
        extent = [x0, upper[0], y0, upper[1]]
    else:
        extent = [0, 0.1, -0.1, 0.3]
    im = ax[0].imshow(Tgas, origin="lower", extent=extent, cmap="inferno", vmin=250, vmax=1900)
    sc = ax[0].scatter(xs, ys, c=p["temperature"].ravel(), s=2, cmap="coolwarm", vmin=300, vmax=max(320, float(p["temperature"].max())))
    ax[0].set_title(f"heat-up, t = {step_time.get(step_of(g_heat), 0):.3g} s")
    fig.colorbar(im, ax=ax[0], label="gas temperature [K]", fraction=0.08, pad=0.02)
    fig.colorbar(sc, ax=ax[0], label="particle temperature [K]", fraction=0.05, pad=0.08, location="bottom")
    ax[0].set_aspect("equal")
    # 2. temperature histories
    names = [c[len("temperature_max_"):] for c in rows[0] if c.startswith("temperature_max_")]
    top = 0
    for n in names:
        tmax = np.array([float(r[f"temperature_max_{n}"]) for r in rows])
        tmean = np.array([float(r[f"temperature_mean_{n}"]) for r in rows])
        line, = ax[1].plot(time, tmax, label=f"{n}: hottest particle")
        ax[1].plot(time, tmean, "--", color=line.get_color(), label=f"{n}: mean")
        heating = time <= (switch_mech if switch_mech and switch_mech > 0 else time[-1])
        top = max(top, float(tmax[heating].max()))
    ax[1].set_ylim(280, top + 0.15 * (top - 280))  # (the burning charge after ignition is off the scale)
    for t, label in ((switch_heat_only, "heat_only"), (switch_mech, "ignition")):
        if t and t > 0:
            ax[1].axvline(t, color="grey", lw=0.8)
            ax[1].text(t, ax[1].get_ylim()[1], f" {label}", va="top", fontsize=8, rotation=90)
    ax[1].set_xscale("symlog", linthresh=0.1)
    ax[1].set_xlabel("time [s] (linear to 0.1 s, then logarithmic)")
    ax[1].set_ylabel("temperature [K]")
    ax[1].set_title("the container heating")
    ax[1].legend(fontsize=8)
    ax[1].grid(alpha=0.3)
    # 3. the end
    _, pres = gas_fields(gas_files[-1])
    p = particles(part_files[-1], z_max)
    im = ax[2].imshow(np.log10(np.maximum(pres, 1e3)), origin="lower", extent=extent, cmap="Blues")
    mat, failed, frag = p["material"].ravel(), p["failed"].ravel() > 0, p["fragment"].ravel()
    charge = mat == 1
    ax[2].scatter(p["coordinates"][charge, 0], p["coordinates"][charge, 1], s=2, color="wheat")
    steel_failed = (mat == 0) & failed
    ax[2].scatter(p["coordinates"][steel_failed, 0], p["coordinates"][steel_failed, 1], s=2, color="grey")
    intact = (mat == 0) & ~failed
    ax[2].scatter(p["coordinates"][intact, 0], p["coordinates"][intact, 1], s=2, c=frag[intact] % 10, cmap="tab10", vmin=0, vmax=9)
    fig.colorbar(im, ax=ax[2], label="log10 gas pressure [Pa]", fraction=0.08)
    ax[2].set_title(f"t = {time[-1]:.6g} s")
    ax[2].set_aspect("equal")
    # 4. after ignition
    if switch_mech and switch_mech > 0:
        sel = time >= switch_mech
        tt = (time[sel] - switch_mech) * 1e6
        pmax = np.array([float(r["gas_max_pressure"]) for r in rows])[sel]
        ax[3].semilogy(tt, pmax, color="tab:red", label="largest cell pressure")
        ax[3].set_ylabel("pressure [Pa]")
        ax[3].set_xlabel("time since ignition [µs]")
        if "expansion_velocity" in rows[0]:
            v = np.array([float(r["expansion_velocity"]) for r in rows])[sel]
            a2 = ax[3].twinx()
            a2.plot(tt, v, color="tab:blue", label="wall's mean radial velocity")
            a2.set_ylabel("velocity [m/s]")
            a2.legend(loc="lower right", fontsize=8)
        ax[3].legend(loc="upper left", fontsize=8)
        ax[3].set_title("the burst")
        ax[3].grid(alpha=0.3)
    fig.suptitle(f"{summary.get('scene', 'run')}: ignition at {switch_mech:.4g} s" if switch_mech and switch_mech > 0 else summary.get("scene", "run"))
    fig.tight_layout()
    path = os.path.join(args.out, args.png)
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
