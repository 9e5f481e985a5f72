#!/usr/bin/python3
"""Fragment count against resolution, with and without a length scale for failure, over porosity seeds.

  scripts/study_fragments.py --burst build/burst [--scene options/scenes/cylinder2d_4340.opts]
                             [--cells 120,240,480] [--ppc 2,3,4] [--regularizations none,nonlocal,crack_band]
                             [--cases 80x2,160x2,160x3] [--ranks 2] [--out output/study] [--plot-only]
                             [--seeds N [--seed0 S]] [--launcher "srun -n {ranks}"] [--jobs K] [--cost-chart]
                             [--extra="-mpm_shape_type bspline2"]

For each regularisation (-steel_regularization: none, nonlocal with --length, crack_band with
--fracture-energy) runs the scene at each cell count (2 x 2 particles per cell) and, at the middle
cell count, at each number of particles per cell (or exactly the --cases CELLSxPPC given), and writes
  OUT/fragments_study.csv  one row per run, appended as each run ends (a long study can be stopped
                           and resumed: rows already there are not run again): count, the
                           Grady-Hightower band, failure energy and plastic work, the fragment masses
  OUT/fragments_study.png  the count against the cell size per regularisation with the Grady band,
                           the failure energy, and the cumulative fragment-mass distributions
With --seeds N every case runs with -MATERIAL_random_seed S, S+1, ..., S+N-1 (the initial porosity and damage
draws; one seed: the scene's own) and the study also writes
  OUT/fragments_ensemble.csv  per case: the count's mean, sample standard deviation and range over the
                           seeds, the first-failure velocity's mean and deviation, the Grady band, the
                           Mott and Grady-Kipp fits of the pooled masses (scripts/fragment_ensemble.py)
  OUT/fragments_ensemble.png  the counts per seed with mean and deviation, and the pooled cumulative
                           mass distributions with both fits and Grady's mean fragment mass
With --cost-chart it writes
  OUT/fragments_cost.csv, .png  per case: the count, first-failure time and expansion velocity at
                           first failure (mean and sample deviation over the seeds) against the
                           median stepping time of its runs, with the Grady band
--extra="..." passes more burst options to every run (with the =, so that argparse reads a value
that starts with a dash). --launcher is the command before burst, {ranks} replaced (default: mpiexec
for --ranks > 1); --jobs K
runs K cases at once (for a launcher that submits to a cluster's queue and waits, e.g. srun).
--quick runs 120 cells (1.5 mm over the 4340 scene's 0.18 m) and 2 particles per cell with the crack
band only (as the scenes ship; without a length the polar-seeded wall erodes nearly whole; the suite's
test study_fragments_quick) and checks it as tests/verify.py grady checks a fragmenting scene: the count within
the gross bracket [Grady shear / 2, 3 x Grady tension] (counts in the softening regime depend on the
mesh: only a gross mismatch fails) and |energy balance error| <= 0.02. Exits non-zero when a run fails,
a --quick check fails, or the CSV or the chart is not written. With --quick and --seeds > 1 it also
checks that the seeds change the fragment masses and that each run's summary.json fits (Mott and
Grady-Kipp) match numpy's least squares on the run's masses to 1e-8.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fragment_ensemble  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
FIELDS = ["regularization", "cells", "particles_per_cell", "seed", "cell_size_mm", "particles", "fragments", "fracture_velocity", "fracture_time", "grady_shear",
          "grady_tension", "failure_energy_J_per_m", "plastic_work_J_per_m", "intact_mass_fraction", "largest_fragment_kg",
          "energy_balance_error", "wall_time_s", "initial_mass", "fragment_masses_kg", "fragment_sizes_m", "mott_N0", "mott_mu_kg",
          "grady_kipp_N0", "grady_kipp_mu_kg"]


def regularization_options(args, reg):
    material = args.material
    if reg == "nonlocal":
        return [f"-{material}_regularization", "nonlocal", f"-{material}_regularization_length", str(args.length)]
    if reg == "crack_band":
        return [f"-{material}_regularization", "crack_band", f"-{material}_fracture_energy", str(args.fracture_energy)]
    return [f"-{material}_regularization", "none"]  # explicit: the cylinder scenes ship the crack band


def fragment_masses(out, summary):
    """The masses and sizes of the counted fragments (the run's -fragments_min_* filters), largest first."""
    rows = list(csv.DictReader(open(os.path.join(out, "fragments.csv"))))
    floor = summary["fragment_min_mass_fraction"] * summary["initial_mass"]
    size = "size_area" if "size_area" in rows[0] else "size_length"
    kept = [(float(r["mass"]), float(r[size])) for r in rows if int(r["particles"]) >= summary["fragment_min_particles"] and float(r["mass"]) >= floor]
    return sorted(kept, reverse=True)


def launcher(args):
    if args.launcher:
        return args.launcher.format(ranks=args.ranks).split()
    return [*MPIEXEC, "-n", str(args.ranks)] if args.ranks > 1 else []


def run(args, reg, cells, ppc, seed=None, extra=()):
    geometry = "wall" if "cylinder" in args.scene else "ring"
    with tempfile.TemporaryDirectory() as out:
        cmd = launcher(args) + [
            args.burst, "-options_file", os.path.join(ROOT, args.scene), "-output_dir", out, "-grid_cells", f"{cells},{cells}",
            f"-{geometry}_particles_per_cell", str(ppc), "-output_interval", "0", "-progress", "false", "-monitor_interval", "100000",
            *regularization_options(args, reg), *([f"-{args.material}_random_seed", str(seed)] if seed is not None else []), *shlex.split(args.extra), *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            raise SystemExit(proc.stdout[-2000:] + proc.stderr[-2000:])
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        kept = fragment_masses(out, s)
    h = (s["grid_upper"][0] - s["grid_lower"][0]) / cells
    fit = s.get("fragment_mass_fit") or {}
    mott, gk = fit.get("mott") or {}, fit.get("grady_kipp") or {}
    return dict(regularization=reg, cells=cells, particles_per_cell=ppc, seed="" if seed is None else seed, cell_size_mm=round(1e3 * h, 6), particles=s["particles"],
                fragments=s["fragment_count"], fracture_velocity=s["fracture_velocity"], fracture_time=s.get("fracture_time", ""), grady_shear=s["grady_shear"]["sector"],
                grady_tension=s["grady_tension"]["sector"], failure_energy_J_per_m=s["failure_energy"], plastic_work_J_per_m=s["plastic_work"],
                intact_mass_fraction=s["intact_mass"] / s["initial_mass"], largest_fragment_kg=s["largest_fragment_mass"],
                energy_balance_error=s["energy_balance_error"], wall_time_s=s["wall_time_s"], initial_mass=s["initial_mass"],
                fragment_masses_kg=";".join(f"{m!r}" for m, _ in kept), fragment_sizes_m=";".join(f"{z:.6g}" for _, z in kept),
                mott_N0=mott.get("N0", ""), mott_mu_kg=mott.get("mu", ""), grady_kipp_N0=gk.get("N0", ""), grady_kipp_mu_kg=gk.get("mu", ""))


def plot(rows, args, png):
    regs = [r for r in ("none", "nonlocal", "crack_band") if any(x["regularization"] == r for x in rows)]
    labels = {"none": "no length", "nonlocal": f"nonlocal, ell = {1e3 * args.length:g} mm", "crack_band": f"crack band, G_f = {args.fracture_energy / 1e3:g} kJ/m^2"}
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    ax = axes[0]
    for i, reg in enumerate(regs):
        base = sorted((r for r in rows if r["regularization"] == reg and int(r["particles_per_cell"]) == 2), key=lambda r: float(r["cell_size_mm"]))
        ax.plot([float(r["cell_size_mm"]) * (1 + 0.03 * i) for r in base], [int(r["fragments"]) for r in base], "o-", color=f"C{i}", label=labels[reg] + ", 2 x 2 per cell")
        for r in rows:
            if r["regularization"] == reg and int(r["particles_per_cell"]) != 2:
                k = int(r["particles_per_cell"])
                ax.plot(float(r["cell_size_mm"]) * (1 + 0.03 * i), int(r["fragments"]), "s^v"[k % 3], color=f"C{i}", mfc="none", ms=8 + 2 * k)
                ax.annotate(f"{k}x{k}", (float(r["cell_size_mm"]) * (1 + 0.03 * i), int(r["fragments"])), fontsize=7, xytext=(6, -3), textcoords="offset points")
    for r in rows:
        ax.plot([float(r["cell_size_mm"])] * 2, [float(r["grady_shear"]), float(r["grady_tension"])], color="0.5", lw=6, alpha=0.25)
    ax.plot([], [], color="0.5", lw=6, alpha=0.4, label="Grady-Hightower, shear-tension")
    ax.axhspan(6, 7, color="C3", alpha=0.1, label="paper: 6-7")
    ax.set_xlabel("cell size (mm)")
    ax.set_ylabel("fragments on the quarter")
    ax.set_ylim(top=max(int(r["fragments"]) for r in rows) + 5)
    ax.set_title(os.path.basename(args.scene).replace(".opts", "") + ": count (squares: 3x3, 4x4 per cell)", fontsize=9)
    ax.legend(fontsize=7)
    ax = axes[1]
    for i, reg in enumerate(regs):
        sel = sorted((r for r in rows if r["regularization"] == reg), key=lambda r: (int(r["particles_per_cell"]), float(r["cell_size_mm"])))
        base = [r for r in sel if int(r["particles_per_cell"]) == 2]
        ax.plot([float(r["cell_size_mm"]) for r in base], [float(r["failure_energy_J_per_m"]) for r in base], "o-", color=f"C{i}", label=labels[reg])
        for r in sel:
            if int(r["particles_per_cell"]) != 2:
                ax.plot(float(r["cell_size_mm"]), float(r["failure_energy_J_per_m"]), "s", color=f"C{i}", mfc="none")
    ax.set_xlabel("cell size (mm)")
    ax.set_ylabel("energy dissipated in failure (J/m)")
    ax.set_yscale("log")
    ax.set_title("failure energy (erosion: released elastic energy; crack band: softening work)", fontsize=9)
    ax.legend(fontsize=7)
    plot_mass_distribution(axes[2], rows, regs, lambda r: f"{labels[r['regularization']]}: {r['cells']} cells, {r['particles_per_cell']}x{r['particles_per_cell']}", fade=0.12)
    fig.savefig(png, dpi=120, bbox_inches="tight")


def write_table(path, rows, fields):
    """The study's CSV, rewritten whole."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def plot_mass_distribution(ax, rows, regs, label, fade):
    """Cumulative fragment-mass distribution of every run, one colour per regularisation."""
    for i, reg in enumerate(regs):
        for j, r in enumerate(r for r in rows if r["regularization"] == reg):
            masses = sorted((float(m) for m in r["fragment_masses_kg"].split(";") if m), reverse=True)
            if masses:
                ax.step(masses, range(1, len(masses) + 1), where="post", color=f"C{i}", alpha=max(0.15, 0.9 - fade * j), label=label(r))
    ax.set_xscale("log")
    ax.set_xlabel("fragment mass m (kg per m of length)")
    ax.set_ylabel("fragments of mass >= m")
    ax.set_title("cumulative fragment-mass distribution", fontsize=9)
    ax.legend(fontsize=6)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--scene", default="options/scenes/cylinder2d_4340.opts")
    p.add_argument("--material", default="steel")
    p.add_argument("--cells", default="120,240,480")  # 1.5, 0.75, 0.375 mm over the 4340 scene's 0.18 m (the others: 100,200,400)
    p.add_argument("--ppc", default="2,3,4")
    p.add_argument("--cases", default="", help="explicit CELLSxPPC list, in the order to run (instead of --cells/--ppc)")
    p.add_argument("--regularizations", default="none,nonlocal,crack_band")
    p.add_argument("--length", type=float, default=2e-3, help="ell of -MAT_regularization nonlocal (m)")
    p.add_argument("--fracture-energy", type=float, default=2.8e4, help="G_f of -MAT_regularization crack_band (J/m^2); "
                   "4340: K_IC^2 (1 - nu^2)/E = (80 MPa m^0.5)^2 0.91 / 208 GPa")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default=os.path.join(ROOT, "output/study"))
    p.add_argument("--quick", action="store_true")
    p.add_argument("--plot-only", action="store_true")
    p.add_argument("--seeds", type=int, default=1, help="porosity/damage seeds per case (-MATERIAL_random_seed); 1: the scene's own seed")
    p.add_argument("--seed0", type=int, default=1, help="the first seed of --seeds")
    p.add_argument("--launcher", default="", help="command before burst, {ranks} replaced, e.g. 'srun -n {ranks}' (default: mpiexec)")
    p.add_argument("--jobs", type=int, default=1, help="runs at once")
    p.add_argument("--extra", default="", help="more burst options for every run, given as --extra='-mpm_shape_type bspline2'")
    p.add_argument("--cost-chart", action="store_true", help="also the count, first-failure time and velocity (mean and deviation over the seeds) against "
                   "the run's cost, per case: OUT/fragments_cost.csv and .png")
    args = p.parse_args()
    regs = ["crack_band"] if args.quick else args.regularizations.split(",")
    if args.cases and not args.quick:
        cases = [tuple(int(v) for v in c.split("x")) for c in args.cases.split(",")]
    else:
        cells = [120] if args.quick else [int(c) for c in args.cells.split(",")]
        ppcs = [2] if args.quick else [int(c) for c in args.ppc.split(",")]
        middle = cells[len(cells) // 2]
        cases = [(c, 2) for c in cells] + [(middle, k) for k in ppcs if k != 2]
    os.makedirs(args.out, exist_ok=True)
    table = os.path.join(args.out, "fragments_study.csv")
    rows = list(csv.DictReader(open(table))) if os.path.exists(table) and not args.quick else []
    seeds = [None] if args.seeds <= 1 else list(range(args.seed0, args.seed0 + args.seeds))
    if not args.plot_only:
        def done(reg, c, k, seed):
            return any(r["regularization"] == reg and int(r["cells"]) == c and int(r["particles_per_cell"]) == k and str(r.get("seed", "")) == ("" if seed is None else str(seed)) for r in rows)
        # resolution-major: every regularisation and seed at one resolution before the next
        todo = [(reg, c, k, seed) for c, k in cases for reg in regs for seed in seeds if not done(reg, c, k, seed)]
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for row in pool.map(lambda job: run(args, *job), todo):
                rows.append(row)
                write_table(table, rows, FIELDS)  # after every run: an interrupted study keeps what it has
                print(f"{row['regularization']:10s} {row['cells']:4d} cells, {row['particles_per_cell']} per cell{'' if row['seed'] == '' else ', seed ' + str(row['seed'])}: "
                      f"{row['fragments']:3d} fragments, Grady {row['grady_shear']:.2f}-{row['grady_tension']:.2f}, "
                      f"V {row['fracture_velocity']:.0f} m/s, failure energy {row['failure_energy_J_per_m']:.3g} J/m, intact {row['intact_mass_fraction']:.3f}, "
                      f"energy error {row['energy_balance_error']:.1e}, {row['wall_time_s']:.0f} s", flush=True)
    ensemble_csv, ensemble_png = os.path.join(args.out, "fragments_ensemble.csv"), os.path.join(args.out, "fragments_ensemble.png")
    if args.seeds > 1:
        chosen = [r for r in rows if str(r.get("seed", "")) in {str(x) for x in seeds}]
        ensemble = fragment_ensemble.plot_ensemble(chosen, ensemble_png, os.path.basename(args.scene).replace(".opts", ""))
        write_table(ensemble_csv, ensemble, fragment_ensemble.ENSEMBLE_FIELDS)
        fragment_ensemble.print_ensemble(ensemble)
        print("wrote", ensemble_csv, "and", ensemble_png)
    cost_csv, cost_png = os.path.join(args.out, "fragments_cost.csv"), os.path.join(args.out, "fragments_cost.png")
    if args.cost_chart:
        chosen = [r for r in rows if args.seeds <= 1 or str(r.get("seed", "")) in {str(x) for x in seeds}]
        cost = plot_cost(chosen, cost_png, os.path.basename(args.scene).replace(".opts", ""), args.ranks)
        write_table(cost_csv, cost, COST_FIELDS)
        print("wrote", cost_csv, "and", cost_png)
    png = os.path.join(args.out, "fragments_study.png")
    plot(rows, args, png)
    print("wrote", table, "and", png)
    written = ((table, png, ensemble_csv, ensemble_png) if args.seeds > 1 else (table, png)) + ((cost_csv, cost_png) if args.cost_chart else ())
    failures = [f"{path} not written" for path in written if not os.path.exists(path) or not os.path.getsize(path)]
    if args.quick:
        failures += quick_checks(rows)
        if args.seeds > 1:
            failures += ensemble_checks(rows)
        if args.seeds > 1 and args.cost_chart:
            # the cost chart's statistics against fragment_ensemble's, computed apart
            for c in cost:
                e = next(x for x in ensemble if x["regularization"] == c["regularization"] and int(x["cells"]) == c["cells"] and int(x["particles_per_cell"]) == c["particles_per_cell"])
                worst = max(abs(float(c[a]) - float(e[b])) / max(abs(float(e[b])), 1e-300) for a, b in (("fragments_mean", "fragments_mean"), ("fragments_sd", "fragments_std"),
                                                                                                         ("fracture_velocity_mean", "fracture_velocity_mean")))
                ok = worst <= 1e-12 and c["runs"] == len(seeds)
                print(f"  cost chart, {c['cells']} cells: {c['runs']} runs, count {c['fragments_mean']:.3g} +- {c['fragments_sd']:.3g}, the ensemble's to {worst:.1e} (tol 1e-12): {'OK' if ok else 'FAIL'}")
                if not ok:
                    failures.append("the cost chart's statistics differ from the ensemble's")
    if failures:
        print(f"study_fragments: FAIL ({'; '.join(failures)})")
        sys.exit(1)
    print("study_fragments: OK")


COST_FIELDS = ["regularization", "cells", "particles_per_cell", "runs", "ranks", "stepping_s_median", "stepping_s_min", "stepping_s_max", "particles",
               "fragments_mean", "fragments_sd", "grady_shear_mean", "grady_tension_mean", "fracture_time_us_mean", "fracture_time_us_sd",
               "fracture_velocity_mean", "fracture_velocity_sd"]


def mean_sd(values):
    """Mean and sample standard deviation (0 for a single value)."""
    n = len(values)
    if not n:
        return float("nan"), float("nan")
    m = sum(values) / n
    return m, (sum((v - m) ** 2 for v in values) / (n - 1)) ** 0.5 if n > 1 else 0.0


def plot_cost(rows, png, title, ranks):
    """What a user pays for what: per case (regularisation, cells, particles per cell), the fragment
    count, the first-failure time and the expansion velocity at first failure, each as mean and
    sample deviation over the seeds, against the median stepping time of the case's runs."""
    cases = sorted({(r["regularization"], int(r["cells"]), int(r["particles_per_cell"])) for r in rows}, key=lambda c: (c[0], c[2], c[1]))
    out = []
    for reg, cells, ppc in cases:
        sel = [r for r in rows if r["regularization"] == reg and int(r["cells"]) == cells and int(r["particles_per_cell"]) == ppc]
        walls = sorted(float(r["wall_time_s"]) for r in sel)
        counts = [float(r["fragments"]) for r in sel]
        times = [1e6 * float(r["fracture_time"]) for r in sel if r.get("fracture_time") not in ("", None) and float(r["fracture_time"]) > 0]
        speeds = [float(r["fracture_velocity"]) for r in sel if float(r["fracture_velocity"]) > 0]
        fm, fs = mean_sd(counts)
        tm, ts = mean_sd(times)
        vm, vs = mean_sd(speeds)
        out.append(dict(regularization=reg, cells=cells, particles_per_cell=ppc, runs=len(sel), ranks=ranks, stepping_s_median=statistics.median(walls),
                        stepping_s_min=walls[0], stepping_s_max=walls[-1], particles=sel[0]["particles"], fragments_mean=fm, fragments_sd=fs,
                        grady_shear_mean=mean_sd([float(r["grady_shear"]) for r in sel])[0], grady_tension_mean=mean_sd([float(r["grady_tension"]) for r in sel])[0],
                        fracture_time_us_mean=tm, fracture_time_us_sd=ts, fracture_velocity_mean=vm, fracture_velocity_sd=vs))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for reg in sorted({c["regularization"] for c in out}):
        sel = [c for c in out if c["regularization"] == reg]
        x = [c["stepping_s_median"] for c in sel]
        xerr = [[c["stepping_s_median"] - c["stepping_s_min"] for c in sel], [c["stepping_s_max"] - c["stepping_s_median"] for c in sel]]
        for ax, key, label in ((axes[0], "fragments", "fragments (mean, sd over seeds)"), (axes[1], "fracture_time_us", "first failure (µs)"),
                               (axes[2], "fracture_velocity", "expansion velocity at first failure (m/s)")):
            ax.errorbar(x, [c[key + "_mean"] for c in sel], yerr=[c[key + "_sd"] for c in sel], xerr=xerr, marker="o", capsize=3, label=reg)
            for c in sel:
                ax.annotate(f"{c['cells']}" + ("" if c["particles_per_cell"] == 2 else f" {c['particles_per_cell']}x{c['particles_per_cell']}"),
                            (c["stepping_s_median"], c[key + "_mean"]), textcoords="offset points", xytext=(4, 4), fontsize=8)
            ax.set_xscale("log")
            ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # (the decades label the axis; minor labels overlap)
            ax.set_xlabel(f"stepping time on {ranks} rank(s), s (median, range over seeds)")
            ax.set_ylabel(label)
        axes[0].vlines(x, [c["grady_shear_mean"] for c in sel], [c["grady_tension_mean"] for c in sel], colors="gray", alpha=0.35, linewidth=8, label=f"Grady band ({reg})")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{title}: what resolution buys, over {max(c['runs'] for c in out)} porosity seeds per case")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return out


# The bounds of tests/verify.py grady (a fragmenting scene against Grady-Hightower): measured on the 4340
# scene at 120 cells, 2 per cell, crack band, seeds 1-8: 6-8 fragments against the bracket [2.4, 21.8]
# (Grady 4.8-7.3), energy error -8.7e-3.
ENERGY_TOL = 0.02


def quick_checks(rows, label=lambda r: f"{r['regularization']} {r['cells']} cells"):
    """The quick form's verdicts per row (also scripts/study_failure.py): the fragment count within
    [Grady shear / 2, 3 x Grady tension] and |energy balance error| <= ENERGY_TOL. Returns the failures."""
    failures = []
    for r in rows:
        name = label(r)
        n, lo, hi, e = int(r["fragments"]), float(r["grady_shear"]), float(r["grady_tension"]), float(r["energy_balance_error"])
        ok = 0.5 * lo <= n <= 3 * hi
        print(f"  {name}: {n} fragments within [shear/2, 3 x tension] = [{0.5 * lo:.2f}, {3 * hi:.2f}]: {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"{name}: {n} fragments")
        ok = abs(e) <= ENERGY_TOL
        print(f"  {name}: |energy balance error| {abs(e):.2e} <= {ENERGY_TOL:g}: {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"{name}: energy balance error {e:+.2e}")
    return failures


def ensemble_checks(rows):
    """The seeds reach the porosity draws (the runs' fragment masses differ), and burst's per-run fits
    (summary.json fragment_mass_fit) equal numpy's least squares of ln k on m^(1/2) and on m."""
    import numpy as np

    failures = []
    distinct = len({r["fragment_masses_kg"] for r in rows})
    ok = distinct == len(rows)
    print(f"  {len(rows)} seeds give {distinct} different sets of fragment masses: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("seeds that give the same fragments")
    worst = 0.0
    for r in rows:
        masses = np.array(sorted(fragment_ensemble.masses_of(r), reverse=True))
        if len(masses) < 3:
            continue
        lnk = np.log(np.arange(1, len(masses) + 1))
        for kind, x in (("mott", np.sqrt(masses)), ("grady_kipp", masses)):
            slope, intercept = np.polyfit(x, lnk, 1)
            mu = 1 / slope ** 2 if kind == "mott" else -1 / slope
            for name, mine, theirs in ((f"{kind}_N0", float(r[f"{kind}_N0"]), np.exp(intercept)), (f"{kind}_mu", float(r[f"{kind}_mu_kg"]), mu)):
                worst = max(worst, abs(mine - theirs) / abs(theirs))
    ok = worst <= 1e-8
    print(f"  summary.json's Mott and Grady-Kipp fits against numpy's: largest relative difference {worst:.2e} (tol 1e-8): {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("fits differ from numpy's")
    return failures


if __name__ == "__main__":
    main()
