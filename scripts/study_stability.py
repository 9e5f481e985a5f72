#!/usr/bin/python3
"""Where methods fail: the largest stable Courant number of each interpolator x transfer x step order,
and the energy histories of FLIP, PIC, APIC and XPIC.

  scripts/study_stability.py --burst build/burst [--out doc/figures] [--quick]

Problem: the colliding elastic disks (options/scenes/colliding_disks.opts, 20 x 20 cells, t = 3 s).
A run counts as stable when it reaches the final time without burst stopping it: the energy check
-mpm_energy_growth_limit 0.01 (the total energy may not grow by more than 1 % of the largest energy
seen), the NaN check and the J <= 0 check all stop an unstable run with its step, particle and cause.
For each method the CFL numbers are tried in increasing order up to the first failure.
Writes OUT/stability_cfl.csv, OUT/stability_cfl.png (the map: largest stable CFL per method) and
OUT/energy_histories.png (total energy against time at CFL 0.2, MUSL, linear and cpGIMP).
--quick: two methods, two CFL numbers, no histories (the suite's smoke test)."""
import argparse
import csv
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "options/scenes/colliding_disks.opts")
TRANSFERS = {"FLIP": [], "PIC": ["-mpm_flip_fraction", "0"], "APIC": ["-mpm_transfer", "apic"], "XPIC(2)": ["-mpm_transfer", "xpic", "-mpm_xpic_order", "2"]}


def run(burst, extra, history=False):
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", DECK, "-output_dir", out, "-progress", "false", "-output_interval", "0", "-output_grid", "false",
               "-monitor_interval", "10", "-mpm_energy_growth_limit", "0.01", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        reason = ""
        if proc.returncode:
            text = proc.stdout + proc.stderr
            reason = "energy growth" if "unstable: the total energy grew" in text else ("NaN" if "not finite" in text else ("J <= 0" if "det F <= 0" in text else "other"))
        hist = None
        if history and not proc.returncode:
            data = np.genfromtxt(os.path.join(out, "monitor.csv"), delimiter=",", names=True)
            hist = (data["time"], data["total"] - data["external_work"])
        return proc.returncode == 0, reason, hist


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--out", default=os.path.join(ROOT, "doc/figures"))
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    cfls = [0.1, 0.2] if a.quick else [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0]
    shapes = ["linear"] if a.quick else ["linear", "ugimp", "cpgimp", "bspline2"]
    transfers = ["FLIP", "APIC"] if a.quick else list(TRANSFERS)
    schemes = ["musl"] if a.quick else ["usl", "musl", "usf"]
    rows = []
    for scheme in schemes:
        for shape in shapes:
            for tr in transfers:
                best, why = 0.0, "stable to the largest CFL tried"
                for cfl in cfls:
                    ok, reason, _ = run(a.burst, ["-mpm_shape_type", shape, "-mpm_scheme", scheme, "-mpm_cfl", str(cfl), *TRANSFERS[tr]])
                    if not ok:
                        why = f"{reason} at CFL {cfl}"
                        break
                    best = cfl
                rows.append(dict(scheme=scheme, shape=shape, transfer=tr, largest_stable_cfl=best, failure=why))
                print(f"{scheme} {shape} {tr}: largest stable CFL {best} ({why})", flush=True)
    path = os.path.join(a.out, "stability_cfl.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    cols = [(sc, tr) for sc in schemes for tr in transfers]
    grid = np.array([[next(r["largest_stable_cfl"] for r in rows if r["shape"] == sh and r["scheme"] == sc and r["transfer"] == tr) for sc, tr in cols] for sh in shapes])
    fig, ax = plt.subplots(figsize=(1.0 + 0.6 * len(cols), 1.2 + 0.5 * len(shapes)))
    im = ax.imshow(grid, cmap="viridis", vmin=0, vmax=max(cfls), aspect="auto")
    for i in range(len(shapes)):
        for j in range(len(cols)):
            ax.text(j, i, f"{grid[i, j]:g}", ha="center", va="center", color="w" if grid[i, j] < 0.5 * max(cfls) else "k", fontsize=7)
    ax.set_xticks(range(len(cols)), [f"{sc}\n{tr}" for sc, tr in cols], fontsize=6)
    ax.set_yticks(range(len(shapes)), shapes, fontsize=7)
    fig.colorbar(im, ax=ax, label="largest stable CFL")
    ax.set_title("colliding disks: largest stable Courant number (energy growth < 1 %, no NaN, J > 0)", fontsize=8)
    fig.tight_layout()
    png = os.path.join(a.out, "stability_cfl.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    if a.quick:
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharey=True)
    for ax, shape in zip(axes, ["linear", "cpgimp"]):
        for tr in TRANSFERS:
            ok, reason, hist = run(a.burst, ["-mpm_shape_type", shape, "-mpm_scheme", "musl", "-mpm_cfl", "0.1", *TRANSFERS[tr]], history=True)
            if hist is not None:
                ax.plot(hist[0], hist[1] / hist[1][0], label=tr)
        ax.set_title(f"{shape}, MUSL, CFL 0.1", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("total energy / initial")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    png = os.path.join(a.out, "energy_histories.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
