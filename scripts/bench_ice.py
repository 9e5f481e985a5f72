#!/usr/bin/python3
"""Gas (ICE) benchmarks; they print tables and never fail on time.

  pressure preconditioners: the semi-implicit pressure (CG, rtol 1e-10) with Jacobi, PCMG (Galerkin,
      coarsest grid 5 cells a side), GAMG, hypre BoomerAMG and, in 3-D, hypre PFMG (on a
      MATHYPRESTRUCT matrix, -ice_pressure_dm_mat_type hyprestruct) on two problems:
        blast     options/scenes/blast2d.opts / tests/decks/blast3d.opts at the default CFL
                  (acoustic Courant number about 0.125: the matrix is strongly diagonal)
        low_mach  tests/decks/low_mach_spot.opts in 2-D/3-D (u = 1 m/s air, entropy spot) at
                  u dt/h = 0.1, i.e. about 35 x the acoustic limit: what the semi-implicit path is for
      2-D 65^2, 129^2, 257^2 and 3-D 33^3, 65^3 cells (M - 1 = 2^k, as PCMG needs; petsc.md 6), a
      fixed number of steps; KSP iterations per solve, wall time per step (stepping only, from
      summary.json) and of the pressure phase (ICE_Pressure in -log_view).
  throughput: cell-updates per second per core (summary.json gas.cell_steps_per_second_per_core,
      stepping wall time only) for one and four gases (tests/decks/gas_mix_box.opts), 2-D and 3-D,
      explicit and semi-implicit (default preconditioner), three sizes each.
Usage: scripts/bench_ice.py --burst build/burst [--quick] [--csv DIR] [--only pc|throughput] [--ranks N]"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from bench import MPIEXEC, cpu_name  # scripts/bench.py: the same launcher and machine line


def mg_levels(n, coarsest=5):
    """PCMG levels for n cells a side: halve (n - 1) down to a coarsest grid of `coarsest` cells."""
    return int(round(math.log2((n - 1) / (coarsest - 1)))) + 1


def preconditioners(dim, n):
    pcs = [("jacobi", ["-ice_pressure_pc_type", "jacobi"]),
           ("mg", ["-ice_pressure_pc_type", "mg", "-ice_pressure_pc_mg_levels", str(mg_levels(n)), "-ice_pressure_pc_mg_galerkin", "both"]),
           ("gamg", ["-ice_pressure_pc_type", "gamg"]),
           ("boomeramg", ["-ice_pressure_pc_type", "hypre", "-ice_pressure_pc_hypre_type", "boomeramg"])]
    if dim == 3:
        pcs.append(("pfmg", ["-ice_pressure_dm_mat_type", "hyprestruct", "-ice_pressure_pc_type", "pfmg"]))
    return pcs


def problem(name, dim, n):
    """(deck, options) of a benchmark problem with n cells a side."""
    if name == "blast":
        deck = "options/scenes/blast2d.opts" if dim == 2 else "tests/decks/blast3d.opts"
        return deck, ["-grid_cells", ",".join([str(n)] * dim), "-ice_pressure_solver", "semi_implicit"]
    # low_mach: the entropy spot of the verification, in a square/cube box with walls on the sides
    deck = "tests/decks/low_mach_spot.opts"
    opts = ["-ice_pressure_solver", "semi_implicit", "-ice_dt", repr(0.1 / n), "-final_time", "1"]
    if dim == 2:
        opts += ["-grid_cells", f"{n},{n}", "-grid_upper", "1,1", "-ice_perturbation_center", "0.25,0.5", "-ice_bc_ymin", "wall", "-ice_bc_ymax", "wall"]
    else:
        opts += ["-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", f"{n},{n},{n}", "-air_velocity", "1,0,0",
                 "-ice_inflow_xmin", "1.1768293,1,0,0,300", "-ice_perturbation_center", "0.25,0.5,0.5",
                 "-ice_bc_ymin", "wall", "-ice_bc_ymax", "wall", "-ice_bc_zmin", "wall", "-ice_bc_zmax", "wall"]
    return deck, opts


def run(burst, deck, extra, ranks=1, log_view=False):
    """summary.json and the ICE_Pressure time (s, max over ranks) of one run; None if it failed."""
    with tempfile.TemporaryDirectory() as out:
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [burst, "-options_file", os.path.join(ROOT, deck), "-output_dir", out,
                                                                      "-progress", "false", "-output_interval", "0", "-monitor_interval", "100000",
                                                                      *extra] + (["-log_view"] if log_view else [])
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            lines = [ln.split("PETSC ERROR:", 1)[1].strip() for ln in (proc.stdout + proc.stderr).splitlines() if "PETSC ERROR:" in ln]
            return None, next((ln for ln in lines if ln and not ln.startswith("-") and not ln.startswith("#")), f"exit {proc.returncode}")
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    pressure = sum(float(ln.split()[3]) for ln in proc.stdout.splitlines() if ln.startswith("ICE_Pressure"))
    s["_pressure_time"] = pressure
    return s, ""


def per_step_ms(s, cells, ranks):
    rate = s["gas"]["cell_steps_per_second_per_core"]
    return 1e3 * cells / (rate * ranks) if rate > 0 else float("nan")


def pc_study(args, rows_out):
    sizes = {2: [33, 65] if args.quick else [65, 129, 257], 3: [17, 33] if args.quick else [33, 65]}
    steps = {2: 10, 3: 5}
    for name in ("blast", "low_mach"):
        for dim in (2, 3):
            print(f"\npressure preconditioners, {name}, {dim}-D, CG rtol 1e-10, {steps[dim]} steps, {args.ranks} rank(s): "
                  f"KSP iterations per solve | ms per step (whole step) | ms per step in ICE_Pressure")
            pcs = [p for p, _ in preconditioners(dim, sizes[dim][0])]
            print(f"  {'cells':>9} " + " ".join(f"{p:>22}" for p in pcs))
            for n in sizes[dim]:
                cells = n ** dim
                line = f"  {n:>4}^{dim} = " if False else f"  {str(n) + '^' + str(dim):>9} "
                for pc, opts in preconditioners(dim, n):
                    deck, extra = problem(name, dim, n)
                    s, err = run(args.burst, deck, extra + opts + ["-max_steps", str(steps[dim])], args.ranks, log_view=True)
                    if s is None:
                        line += f" {'failed':>22}"
                        rows_out.append(dict(problem=name, dim=dim, n=n, pc=pc, its="", ms_step="", ms_pressure="", error=err))
                        continue
                    its = s["gas"]["ksp_iterations_per_solve"]
                    ms = per_step_ms(s, cells, args.ranks)
                    msp = 1e3 * s["_pressure_time"] / max(s["steps"], 1)
                    line += f" {its:6.1f} {ms:7.1f} {msp:7.1f}"
                    rows_out.append(dict(problem=name, dim=dim, n=n, pc=pc, its=round(its, 2), ms_step=round(ms, 2), ms_pressure=round(msp, 2), error=""))
                print(line, flush=True)
            for r in rows_out:
                if r["problem"] == name and r["dim"] == dim and r["error"]:
                    print(f"    {r['pc']} at {r['n']}^{dim} failed: {r['error']}")


def throughput(args, rows_out):
    sizes = {2: [65, 129] if args.quick else [65, 129, 257], 3: [17, 33] if args.quick else [17, 33, 65]}
    steps = {2: 10, 3: 5}
    deck = "tests/decks/gas_mix_box.opts"
    print(f"\ngas throughput ({deck}, default preconditioner), {args.ranks} rank(s): million cell-updates per second per core "
          f"(stepping wall time from summary.json); four-gas semi-implicit at -ice_outer_tolerance {args.outer_tolerance_4:g}")
    print(f"  {'dim':>3} {'cells':>9} | {'1 gas expl':>10} {'1 gas semi':>10} | {'4 gas expl':>10} {'4 gas semi':>10} | {'KSP/solve 1|4':>13}")
    for dim in (2, 3):
        for n in sizes[dim]:
            line = f"  {dim:>3} {str(n) + '^' + str(dim):>9} |"
            its = []
            for nmat in (1, 4):
                for solver in ("explicit", "semi_implicit"):
                    extra = ["-grid_cells", ",".join([str(n)] * dim), "-ice_pressure_solver", solver, "-max_steps", str(steps[dim])]
                    if dim == 3:
                        extra += ["-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-ice_perturbation_center", "0.5,0.5,0.5",
                                  "-ice_bc_zmin", "wall", "-ice_bc_zmax", "wall"]
                    if nmat == 1:
                        extra += ["-ice_materials", "a", "-ice_uniform_volume_fraction", "1"]
                    elif solver == "semi_implicit":
                        # four gases with the default stiff exchange (K 1e15): the outer residual
                        # stalls near 2e-8 on small 3-D grids, above the default 1e-8
                        extra += ["-ice_outer_tolerance", repr(args.outer_tolerance_4)]
                    s, err = run(args.burst, deck, extra, args.ranks)
                    if s is None:
                        line += f" {'failed':>10}"
                        rows_out.append(dict(dim=dim, n=n, materials=nmat, solver=solver, mcell_steps_per_s_per_core="", ksp_its="", error=err))
                        continue
                    rate = s["gas"]["cell_steps_per_second_per_core"]
                    if solver == "semi_implicit":
                        its.append(s["gas"]["ksp_iterations_per_solve"])
                    line += f" {rate / 1e6:10.3f}"
                    rows_out.append(dict(dim=dim, n=n, materials=nmat, solver=solver, mcell_steps_per_s_per_core=round(rate / 1e6, 4),
                                         ksp_its=round(s["gas"]["ksp_iterations_per_solve"], 2), error=""))
                line += " |" if nmat == 1 else ""
            line += " | " + "|".join(f"{i:.1f}" for i in its).rjust(13)
            print(line, flush=True)


def write_csv(path, rows):
    if not rows:
        return
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--quick", action="store_true", help="smaller sizes (a smoke test)")
    p.add_argument("--only", choices=("pc", "throughput"), help="run one part only")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--outer-tolerance-4", type=float, default=1e-7, help="-ice_outer_tolerance of the four-gas semi-implicit runs")
    p.add_argument("--csv", help="directory for ice_preconditioners.csv and ice_throughput.csv")
    args = p.parse_args(argv)
    args.burst = os.path.abspath(args.burst)
    print(f"burst gas (ICE) benchmark on {cpu_name()}, {os.cpu_count()} cores")
    pc_rows, tp_rows = [], []
    if args.only in (None, "pc"):
        pc_study(args, pc_rows)
    if args.only in (None, "throughput"):
        throughput(args, tp_rows)
    if args.csv:
        os.makedirs(args.csv, exist_ok=True)
        write_csv(os.path.join(args.csv, "ice_preconditioners.csv"), pc_rows)
        write_csv(os.path.join(args.csv, "ice_throughput.csv"), tp_rows)


if __name__ == "__main__":
    sys.exit(main())
