#!/usr/bin/python3
"""The expanding ring (Mott/Grady; options/scenes/ring2d.opts): the spread of the fragment count from
the grid against the spread from the random initial porosity and damage (issue 12).

  scripts/study_ring.py --burst build/burst [--cells 80,120,160] [--seed-cells 120]
                        [--seeds 20261122,1,2] [--regularizations none,crack_band] [--ranks 1]
                        [--out doc/figures] [--plot-only]

For each regularisation (none; crack_band with G_f = --fracture-energy) runs the ring at each cell
count with the scene's seed (-steel_random_seed, the first of --seeds), and at --seed-cells with every
seed of --seeds (2 x 2 particles per cell throughout), and writes
  OUT/ring_study.csv  one row per run, appended as each run ends (rows already there are not rerun):
                      count, the Grady-Hightower band of the run, failure energy, fragment masses
  OUT/ring_study.png  the count against the cell size (the seeds as a column of markers at
                      --seed-cells) with the Grady band, and the cumulative fragment-mass distributions
Runs use scripts/study_fragments.py's runner (the scene's own fragment filters).
"""
import argparse
import csv
import os
import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import study_fragments as sf  # noqa: E402

FIELDS = sf.FIELDS


def plot(rows, args, png):
    regs = [r for r in ("none", "crack_band") if any(x["regularization"] == r for x in rows)]
    labels = {"none": "no length", "crack_band": f"crack band, G_f = {args.fracture_energy / 1e3:g} kJ/m^2"}
    base_seed = args.seeds.split(",")[0]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    ax = axes[0]
    for r in rows:
        ax.plot([float(r["cell_size_mm"])] * 2, [float(r["grady_shear"]), float(r["grady_tension"])], color="0.5", lw=6, alpha=0.25)
    for i, reg in enumerate(regs):
        sel = [r for r in rows if r["regularization"] == reg]
        grid = sorted((r for r in sel if r["seed"] == base_seed), key=lambda r: float(r["cell_size_mm"]))
        dx = 1 + 0.03 * (i - 0.5)
        ax.plot([float(r["cell_size_mm"]) * dx for r in grid], [int(r["fragments"]) for r in grid], "o-", color=f"C{i}",
                label=f"{labels[reg]}: grid (seed {base_seed})")
        seeds = [r for r in sel if int(r["cells"]) == args.seed_cells]
        ax.plot([float(r["cell_size_mm"]) * dx * 1.015 for r in seeds], [int(r["fragments"]) for r in seeds], "x", color=f"C{i}", ms=9,
                label=f"{labels[reg]}: {len(seeds)} seeds at {args.seed_cells} cells")
    ax.plot([], [], color="0.5", lw=6, alpha=0.4, label="Grady-Hightower, shear-tension")
    ax.set_xlabel("cell size (mm)")
    ax.set_ylabel("fragments on the quarter")
    ax.set_ylim(0, max(int(r["fragments"]) for r in rows) + 4)
    ax.set_title("ring2d (300 m/s, 4340, 600 K): grid against porosity seed", fontsize=9)
    ax.legend(fontsize=7)
    sf.plot_mass_distribution(axes[1], rows, regs, lambda r: f"{labels[r['regularization']]}: {r['cells']} cells, seed {r['seed']}", fade=0.1)
    fig.savefig(png, dpi=120, bbox_inches="tight")


def spread(rows, args):
    """Per regularisation: the range of the count over the grids (scene seed) and over the seeds."""
    base_seed = args.seeds.split(",")[0]
    for reg in ("none", "crack_band"):
        grid = [int(r["fragments"]) for r in rows if r["regularization"] == reg and r["seed"] == base_seed]
        seeds = [int(r["fragments"]) for r in rows if r["regularization"] == reg and int(r["cells"]) == args.seed_cells]
        if grid:
            print(f"{reg:10s} grid {grid}: range {max(grid) - min(grid)}; seeds at {args.seed_cells} cells {seeds}: range "
                  f"{max(seeds) - min(seeds) if seeds else '-'}, sd {statistics.pstdev(seeds) if len(seeds) > 1 else 0:.2f}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(sf.ROOT, "build/burst"))
    p.add_argument("--scene", default="options/scenes/ring2d.opts")
    p.add_argument("--material", default="steel")
    p.add_argument("--cells", default="80,120,160")
    p.add_argument("--seed-cells", type=int, default=120)
    p.add_argument("--seeds", default="20261122,1,2", help="the first is the scene's (-steel_random_seed of steel_4340_paper.opts)")
    p.add_argument("--regularizations", default="none,crack_band")
    p.add_argument("--fracture-energy", type=float, default=2.8e4, help="G_f of -MAT_regularization crack_band (J/m^2)")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--out", default=os.path.join(sf.ROOT, "doc/figures"))
    p.add_argument("--plot-only", action="store_true")
    p.add_argument("--launcher", default="", help="command before burst, {ranks} replaced (default: mpiexec for --ranks > 1)")
    # the form doc/failure.md's ring table was measured in (the scene ships rings over 0.18 m to 360 us)
    p.add_argument("--extra", default="-ring_seeding lattice -grid_upper 0.12,0.12 -final_time 1.2e-4",
                   help="more burst options for every run, given as --extra='...'")
    args = p.parse_args()
    args.length = 0.0
    seeds = args.seeds.split(",")
    cases = [(c, seeds[0]) for c in (int(v) for v in args.cells.split(","))]
    cases += [(args.seed_cells, s) for s in seeds[1:]]
    os.makedirs(args.out, exist_ok=True)
    table = os.path.join(args.out, "ring_study.csv")
    rows = list(csv.DictReader(open(table))) if os.path.exists(table) else []
    if not args.plot_only:
        for c, seed in cases:
            for reg in args.regularizations.split(","):
                if any(r["regularization"] == reg and int(r["cells"]) == c and r["seed"] == seed for r in rows):
                    continue
                row = sf.run(args, reg, c, 2, seed=seed)
                rows.append({k: str(v) for k, v in row.items()})
                sf.write_table(table, rows, FIELDS)
                print(f"{reg:10s} {c:4d} cells, seed {seed}: {row['fragments']:3d} fragments, Grady {row['grady_shear']:.2f}-{row['grady_tension']:.2f}, "
                      f"V {row['fracture_velocity']:.0f} m/s, failure energy {row['failure_energy_J_per_m']:.3g} J/m, intact {row['intact_mass_fraction']:.3f}, "
                      f"{row['wall_time_s']:.0f} s", flush=True)
    spread(rows, args)
    png = os.path.join(args.out, "ring_study.png")
    plot(rows, args, png)
    print("wrote", table, "and", png)


if __name__ == "__main__":
    main()
