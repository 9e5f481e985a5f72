#!/usr/bin/python3
"""Fragment count against resolution: the mesh dependence the paper warns about, measured.

  scripts/study_fragments.py --burst build/burst [--scene options/scenes/cylinder2d_4340.opts]
                             [--cells 80,160,320] [--ppc 2,3,4] [--ranks 2] [--out output/study]

Runs the scene at each cell count (2 x 2 particles per cell) and, at the middle cell count, at each
number of particles per cell, and writes OUT/fragments_study.csv and OUT/fragments_study.png (the
count against the cell size, with the Grady-Hightower band of each run). --quick runs 80 cells and
2 particles per cell only (the suite's smoke test).
"""
import argparse
import csv
import json
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]


def run(args, cells, ppc, out):
    geometry = "wall" if "cylinder" in args.scene else "ring"
    cmd = ([*MPIEXEC, "-n", str(args.ranks)] if args.ranks > 1 else []) + [
        args.burst, "-options_file", os.path.join(ROOT, args.scene), "-output_dir", out, "-grid_cells", f"{cells},{cells}",
        f"-{geometry}_particles_per_cell", str(ppc), "-output_interval", "0", "-progress", "false", "-monitor_interval", "100000"]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if proc.returncode:
        raise SystemExit(proc.stdout[-2000:] + proc.stderr[-2000:])
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--scene", default="options/scenes/cylinder2d_4340.opts")
    p.add_argument("--cells", default="80,160,320")
    p.add_argument("--ppc", default="2,3,4")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default=os.path.join(ROOT, "output/study"))
    p.add_argument("--quick", action="store_true")
    args = p.parse_args()
    cells = [80] if args.quick else [int(c) for c in args.cells.split(",")]
    ppcs = [2] if args.quick else [int(c) for c in args.ppc.split(",")]
    middle = cells[len(cells) // 2]
    cases = [(c, 2) for c in cells] + [(middle, k) for k in ppcs if k != 2]
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for c, k in cases:
        with tempfile.TemporaryDirectory() as out:
            s = run(args, c, k, out)
        h = 0.12 / c
        row = dict(cells=c, particles_per_cell=k, cell_size_mm=1e3 * h, particles=s["particles"], fragments=s["fragment_count"],
                   fracture_velocity=s["fracture_velocity"], grady_shear=s["grady_shear"]["sector"], grady_tension=s["grady_tension"]["sector"],
                   energy_balance_error=s["energy_balance_error"], wall_time_s=s["wall_time_s"])
        rows.append(row)
        print(f"{c:4d} cells, {k} per cell: {row['fragments']:3d} fragments, Grady {row['grady_shear']:.2f}-{row['grady_tension']:.2f}, "
              f"V {row['fracture_velocity']:.0f} m/s, energy error {row['energy_balance_error']:.1e}, {row['wall_time_s']:.0f} s")
    table = os.path.join(args.out, "fragments_study.csv")
    with open(table, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    base = [r for r in rows if r["particles_per_cell"] == 2]
    ax.plot([r["cell_size_mm"] for r in base], [r["fragments"] for r in base], "o-", label="burst, 2 x 2 per cell")
    for r in rows:
        if r["particles_per_cell"] != 2:
            ax.plot(r["cell_size_mm"], r["fragments"], "s", label=f"burst, {r['particles_per_cell']} x {r['particles_per_cell']} per cell")
    for r in base:
        ax.plot([r["cell_size_mm"]] * 2, [r["grady_shear"], r["grady_tension"]], color="0.5", lw=6, alpha=0.4)
    ax.plot([], [], color="0.5", lw=6, alpha=0.4, label="Grady-Hightower, shear-tension")
    ax.axhspan(6, 7, color="C3", alpha=0.15, label="paper: 6-7")
    ax.set_xlabel("cell size (mm)")
    ax.set_ylabel("fragments on the quarter")
    ax.set_title(os.path.basename(args.scene).replace(".opts", "") + ": fragment count against resolution")
    ax.legend(fontsize=8)
    png = os.path.join(args.out, "fragments_study.png")
    fig.savefig(png, dpi=130, bbox_inches="tight")
    print("wrote", table, "and", png)


if __name__ == "__main__":
    main()
