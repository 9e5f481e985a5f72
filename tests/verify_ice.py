#!/usr/bin/python3
"""Verification drivers for burst's ICE gas solver: each subcommand runs option files through the
burst executable, compares profile.csv / monitor.csv with an exact answer, prints the measured
figures with a verdict, and exits non-zero on failure. ctest calls them (tests/CMakeLists.txt, block 4).

  sod           Sod tube (options/scenes/sod.opts) on several grids: L1 errors of density, velocity
                and pressure, observed orders; --compare-orders: second order beats first order
  air           dimensional air tube (options/scenes/shock_tube_air.opts): relative L1 errors and the
                shock position (verification.md 2.2)
  two_gas       two gases, two gammas (tests/decks/two_gas_tube.opts): L1 errors against the exact
                two-gamma solution, sum of volume fractions, gas a left of the contact, one pressure,
                u_a = u_b (ice.md 6.2)
  exchange      uniform two-gas box (tests/decks/exchange_box.opts): temperature and velocity
                differences against the implicit closed form per step, conservation (ice.md 6.3); the
                drag's heat: total energy conserved with it, thermal energy with -ice_drag_heating 0
  parallel      the Sod deck on 1 and 2 ranks: profile.csv agrees
  conservation  blast in a closed box (tests/decks/closed_box.opts): mass, momentum, energy budget
  acoustic      small isentropic Gaussian pulse (tests/decks/acoustic_pulse.opts), explicit and
                semi-implicit pressure at the same dt: the two agree to a fraction of their own error
                against linear acoustics, and both errors fall under refinement
  low_mach      entropy spot at Mach 0.003 (tests/decks/low_mach_spot.opts): semi-implicit at 35 x
                the acoustic time-step limit stays stable, at uniform pressure, with the spot
                translated; explicit at the same dt fails
  self_check    runs every subcommand above against a small built-in finite-volume model and exact
                profiles instead of burst (no executable needed), including runs that must FAIL

The exact solutions come from tests/riemann_exact.py. Read by column name: profile.csv
(`# time <t> step <n>`, then x,pressure,<m>_density,<m>_velocity,<m>_temperature,<m>_volume_fraction
per material) and monitor.csv (gas_mass, gas_momentum_x/y/z, gas_*_energy).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import riemann_exact  # noqa: E402

MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
SOD = "options/scenes/sod.opts"


# ---------------------------------------------------------------------------------------------
# Running and reading

class Burst:
    """Runs the burst executable; returns summary.json."""

    def __init__(self, exe):
        self.exe = exe

    def run(self, deck, out, extra=(), ranks=1):
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [self.exe, "-options_file", os.path.join(ROOT, deck), "-output_dir", out,
                                                                      "-progress", "false", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode != 0:
            sys.stdout.write(proc.stdout[-4000:])
            sys.stdout.write(proc.stderr[-4000:])
            raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)

    def try_run(self, deck, out, extra=(), ranks=1):
        """Like run, for a run that may fail: (ok, summary or None, the error message or "")."""
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [self.exe, "-options_file", os.path.join(ROOT, deck), "-output_dir", out,
                                                                      "-progress", "false", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode != 0:
            lines = [ln.split("PETSC ERROR:", 1)[1].strip() for ln in (proc.stdout + proc.stderr).splitlines() if "PETSC ERROR:" in ln]
            message = next((ln for ln in lines if ln and not ln.startswith("-") and not ln.startswith("#")), f"exit code {proc.returncode}")
            return False, None, message
        with open(os.path.join(out, "summary.json")) as f:
            return True, json.load(f), ""


def is_option(token):
    return len(token) > 1 and token[0] == "-" and (token[1].isalpha() or token[1] == "_")


def read_options(deck, extra=()):
    """The options of an option file (and the files it includes) with `extra` applied on top, as a
    dict name -> value string ("true" for a bare flag); the last setting wins, as in PETSc."""
    opts = {}

    def load(path):
        with open(path) as f:
            for line in f:
                line = line.split("#", 1)[0].strip()
                if not line:
                    continue
                parts = line.split(None, 1)
                name, value = parts[0], parts[1].strip() if len(parts) > 1 else "true"
                if name == "-options_file":
                    load(os.path.join(ROOT, value))
                else:
                    opts[name] = value

    load(os.path.join(ROOT, deck))
    extra = list(extra)
    k = 0
    while k < len(extra):
        if is_option(extra[k]):
            if k + 1 < len(extra) and not is_option(extra[k + 1]):
                opts[extra[k]] = extra[k + 1]
                k += 2
            else:
                opts[extra[k]] = "true"
                k += 1
        else:
            k += 1
    return opts


def floats(value):
    return [float(v) for v in value.split(",")]


def materials(opts):
    return opts["-ice_materials"].split(",")


def read_profile(out):
    """profile.csv: (time, step, {column: array}) with the rows sorted by x."""
    with open(os.path.join(out, "profile.csv")) as f:
        head = f.readline().replace("#", " ").split()
        time = float(head[head.index("time") + 1])
        step = int(float(head[head.index("step") + 1]))
        rows = list(csv.DictReader(f))
    cols = {k.strip(): np.array([float(r[k]) for r in rows]) for k in rows[0]}
    order = np.argsort(cols["x"], kind="stable")
    return time, step, {k: v[order] for k, v in cols.items()}


def read_monitor(out):
    with open(os.path.join(out, "monitor.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k.strip(): np.array([float(r[k]) for r in rows]) for k in rows[0]}


def mixture(cols, mats):
    """Mixture density (sum of bulk densities), mass-weighted velocity and the pressure."""
    rho = sum(cols[f"{m}_density"] for m in mats)
    u = sum(cols[f"{m}_density"] * cols[f"{m}_velocity"] for m in mats) / rho
    return rho, u, cols["pressure"]


class Riemann:
    """The Riemann problem of an option file (-ice_riemann_*), solved exactly."""

    def __init__(self, opts):
        mats = materials(opts)
        self.left_material = opts.get("-ice_riemann_left_material", mats[0])
        self.right_material = opts.get("-ice_riemann_right_material", mats[0])
        self.gamma_left = float(opts[f"-{self.left_material}_gamma"])
        self.gamma_right = float(opts[f"-{self.right_material}_gamma"])
        self.left = tuple(floats(opts["-ice_riemann_left"]))
        self.right = tuple(floats(opts["-ice_riemann_right"]))
        self.x0 = float(opts["-ice_riemann_position"])
        self.lower = floats(opts["-grid_lower"])[0]
        self.upper = floats(opts["-grid_upper"])[0]
        self.solution = riemann_exact.solve(self.left, self.right, self.gamma_left, self.gamma_right)

    def averages(self, x, t):
        dx = (self.upper - self.lower) / len(x)
        return riemann_exact.cell_average(x, dx, t, self.left, self.right, self.gamma_left, self.gamma_right, self.x0)

    def errors(self, out, opts):
        """L1 errors (mean absolute error over the tube) of the mixture rho, u, p against the exact
        cell averages at the profile's time; also returns the profile and the exact fields."""
        t, step, cols = read_profile(out)
        x = cols["x"]
        rho, u, p = mixture(cols, materials(opts))
        er, eu, ep = self.averages(x, t)
        n = len(x)
        l1 = [float(np.mean(np.abs(a - b))) for a, b in ((rho, er), (u, eu), (p, ep))]
        return l1, dict(t=t, step=step, cols=cols, x=x, rho=rho, u=u, p=p, exact=(er, eu, ep), dx=(self.upper - self.lower) / n)


# ---------------------------------------------------------------------------------------------
# Verdicts

from verify import check, finish  # the verdict lines of every driver (tests/verify.py)


def check_min(name, value, bound, failures, fmt="{:.2f}"):
    ok = value >= bound
    print(f"  {name}: " + fmt.format(value) + f" (>= {bound:g}) {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append(name)


def observed_orders(cells, errors):
    return [math.log(errors[k] / errors[k + 1]) / math.log(cells[k + 1] / cells[k]) if errors[k] > 0 and errors[k + 1] > 0 else float("nan")
            for k in range(len(cells) - 1)]


# ---------------------------------------------------------------------------------------------
# Subcommands

FIELDS = ("density", "velocity", "pressure")


def sod_study(runner, deck, order, cells, extra, ranks=1):
    """L1 errors of (rho, u, p) for each grid; prints the table with observed orders."""
    errors = []
    for n in cells:
        args = ["-grid_cells", f"{n},1", "-ice_advection_order", str(order), *extra]
        opts = read_options(deck, args)
        with tempfile.TemporaryDirectory() as out:
            runner.run(deck, out, args, ranks)
            l1, info = Riemann(opts).errors(out, opts)
        errors.append(l1)
    errors = np.array(errors)
    orders = np.array([observed_orders(cells, errors[:, j]) for j in range(3)]).T
    print(f"{os.path.basename(deck)}, advection order {order}: L1 errors against the exact solution at t = {info['t']:.6g} s (cell averages)")
    print(f"  {'cells':>6} {'density':>10} {'velocity':>10} {'pressure':>10}   {'order rho':>9} {'order u':>8} {'order p':>8}")
    for k, n in enumerate(cells):
        o = "" if k == 0 else f"   {orders[k - 1][0]:9.2f} {orders[k - 1][1]:8.2f} {orders[k - 1][2]:8.2f}"
        print(f"  {n:6d} {errors[k][0]:10.3e} {errors[k][1]:10.3e} {errors[k][2]:10.3e}{o}")
    return errors, orders


def sod(args, runner):
    cells = [int(c) for c in args.cells.split(",")]
    extra = args.extra.split()
    errors, orders = sod_study(runner, args.deck, args.order, cells, extra, args.ranks)
    default_min = 0.6 if args.order == 1 else 0.7
    bounds = [args.min_order_density, args.min_order_velocity, args.min_order_pressure]
    bounds = [default_min if b is None else b for b in bounds]
    max_l1 = args.max_l1 if args.max_l1 is not None else (0.02 if args.order == 1 else 0.01)
    failures = []
    if len(cells) > 1:
        for j, field in enumerate(FIELDS):
            check_min(f"observed order of {field}, {cells[-2]} -> {cells[-1]} cells", orders[-1][j], bounds[j], failures)
    check(f"L1 density error on {cells[-1]} cells", errors[-1][0], max_l1, failures)
    if args.compare_orders:
        other = 2 if args.order == 1 else 1
        errors_other, _ = sod_study(runner, args.deck, other, cells, extra, args.ranks)
        first, second = (errors, errors_other) if args.order == 1 else (errors_other, errors)
        for j, field in enumerate(FIELDS):
            ratio = second[-1][j] / first[-1][j]
            ok = ratio < 1
            print(f"  second order beats first order on {cells[-1]} cells, {field}: L1 ratio {ratio:.3f} < 1 {'OK' if ok else 'FAIL'}")
            if not ok:
                failures.append(f"second order {field}")
    finish(f"sod[order {args.order}]", failures)


# Shocks for the overshoot check (ideal gas, gamma 1.4, on the Sod deck's tube [0, 1]): left, right,
# diaphragm, final time. The Mach 3 shock's left state is the Rankine-Hugoniot post-shock state of a
# Mach 3 shock into (1, 0, 1): p2/p1 = 1 + 2 gamma (M^2 - 1)/(gamma + 1) = 10.3333,
# rho2/rho1 = (gamma + 1) M^2/((gamma - 1) M^2 + 2) = 3.85714, u2 = M c1 (1 - rho1/rho2) = 2.62936
# (c1 = sqrt(1.4)), fed through an inflow face at x = 0 (a wall would send a rarefaction at u + c,
# faster than the shock): one shock at 3.54965 and nothing else. Toro's test 3 (Riemann Solvers,
# Table 4.1) is a pressure ratio of 1e5; from x0 = 0.3 its rarefaction's tail reaches the wall only
# at t = 0.0216, after the final time. Its star region is narrow (0.078 at t = 0.02), hence finer grids.
MACH3_LEFT = (3.857142857142857, 2.6293565924307625, 10.333333333333334)
OVERSHOOT_CASES = {  # left, right, diaphragm, final time, cells, extra options
    "sod": ((1.0, 0.0, 1.0), (0.125, 0.0, 0.1), 0.5, 0.2, (100, 200, 400), []),
    "mach3": (MACH3_LEFT, (1.0, 0.0, 1.0), 0.2, 0.16, (100, 200, 400),
              ["-ice_bc_xmin", "inflow", "-ice_inflow_xmin", f"{MACH3_LEFT[0]!r},{MACH3_LEFT[1]!r},0,{MACH3_LEFT[2] / (MACH3_LEFT[0] * 0.4 * 717.5)!r}"]),
    "ratio1e5": ((1.0, 0.0, 1000.0), (1.0, 0.0, 0.01), 0.3, 0.02, (200, 400, 800), []),
}


def overshoot_measure(x, p, sol, t, x0, dx):
    """Pressure overshoot and dip behind the right-moving shock, as fractions of the shock's jump:
    max (p - p*) over [contact + 3 dx, shock + 3 dx] and max (p* - p) over [contact + 3 dx,
    shock - 4 dx] (the smeared shock itself is left out of the dip)."""
    contact, shock = x0 + sol.u_star * t, x0 + sol.right_head * t
    jump = sol.p_star - sol.right[2]
    behind = (x > contact + 3 * dx) & (x < shock + 3 * dx)
    plateau = (x > contact + 3 * dx) & (x < shock - 4 * dx)
    over = float(np.max(p[behind]) - sol.p_star) / jump
    dip = float(sol.p_star - np.min(p[plateau])) / jump
    return over, dip


def overshoot(args, runner):
    failures = []
    for name in args.cases.split(","):
        left, right, x0, t_end, cells, case_extra = OVERSHOOT_CASES[name]
        cells = [int(c) for c in args.cells.split(",")] if args.cells else cells
        sol = riemann_exact.solve(left, right, 1.4, 1.4)
        print(f"{name}: left {left}, right {right}, x0 {x0}, t {t_end}: p* {sol.p_star:.6g}, shock at {x0 + sol.right_head * t_end:.5f}, jump {sol.p_star - right[2]:.6g}")
        for n in cells:
            extra = ["-grid_cells", f"{n},1", "-ice_riemann_left", ",".join(repr(v) for v in left), "-ice_riemann_right", ",".join(repr(v) for v in right),
                     "-ice_riemann_position", repr(x0), "-final_time", repr(t_end), *case_extra, *args.extra.split()]
            with tempfile.TemporaryDirectory() as out:
                runner.run(SOD, out, extra)
                t, _, cols = read_profile(out)
            over, dip = overshoot_measure(cols["x"], cols["pressure"], sol, t, x0, 1.0 / n)
            check(f"{name} on {n} cells: overshoot / jump", over, args.tol, failures, fmt="{:.4f}")
            check(f"{name} on {n} cells: dip behind / jump", dip, args.tol, failures, fmt="{:.4f}")
    finish("overshoot", failures)


def toro123(args, runner):
    """Toro's test 2 (the "123" problem: two rarefactions leaving a near-vacuum, Riemann Solvers
    Table 4.1): the star pressure (median over the star region) and the velocity oscillation there
    converge under refinement. The density and temperature at the centre keep the error every
    conservative scheme has there (Toro section 6.4: the "entropy glitch"), so they are printed, not
    checked."""
    left, right, x0, t_end = (1.0, -2.0, 0.4), (1.0, 2.0, 0.4), 0.5, 0.15
    sol = riemann_exact.solve(left, right, 1.4, 1.4)
    half = -sol.left_tail * t_end  # the star region is |x - x0| < half
    print(f"123 problem: p* {sol.p_star:.6g}, rho* {sol.rho_star_left:.6g}, u* 0, star region |x - {x0}| < {half:.4f} at t = {t_end} (measured on its inner half)")
    cells = [int(c) for c in args.cells.split(",")]
    failures, errors = [], []
    for n in cells:
        extra = ["-grid_cells", f"{n},1", "-ice_riemann_left", ",".join(map(repr, left)), "-ice_riemann_right", ",".join(map(repr, right)),
                 "-final_time", repr(t_end), *args.extra.split()]
        with tempfile.TemporaryDirectory() as out:
            runner.run(SOD, out, extra)
            t, _, cols = read_profile(out)
        x, p, u, rho = cols["x"], cols["pressure"], cols["gas_velocity"], cols["gas_density"]
        star = np.abs(x - x0) < 0.5 * half  # the inner half: the rarefaction tails are smeared over cells
        error = abs(float(np.median(p[star])) / sol.p_star - 1)
        wiggle = float(np.max(np.abs(u[star])))
        errors.append(error)
        centre = np.argmin(np.abs(x - x0))
        print(f"  {n:5d} cells: star pressure error {error:.4f}, max |u| in the star region's inner half {wiggle:.4f}, centre density {rho[centre]:.4g} (exact {sol.rho_star_left:.4g})")
        if n == cells[-1]:
            check(f"star pressure error on {n} cells", error, args.tol_pressure, failures, fmt="{:.4f}")
            check(f"max |u| in the star region's inner half on {n} cells", wiggle, args.tol_velocity, failures, fmt="{:.4f}")
    orders = observed_orders(cells, np.array(errors))
    check_min(f"observed order of the star pressure, {cells[-2]} -> {cells[-1]} cells", orders[-1], args.min_order, failures)
    finish("t123", failures)


def shock_position(x, p, p_mid):
    """The largest x at which p crosses p_mid going down (linear interpolation between cells)."""
    above = np.nonzero(p >= p_mid)[0]
    if len(above) == 0 or above[-1] == len(x) - 1:
        return float("nan")
    k = above[-1]
    return x[k] + (x[k + 1] - x[k]) * (p[k] - p_mid) / (p[k] - p[k + 1])


def air(args, runner):
    extra = args.extra.split()
    opts = read_options(args.deck, extra)
    problem = Riemann(opts)
    with tempfile.TemporaryDirectory() as out:
        runner.run(args.deck, out, extra, args.ranks)
        l1, info = problem.errors(out, opts)
    rl, _, pl = problem.left
    al = math.sqrt(problem.gamma_left * pl / rl)
    rel = [l1[0] / rl, l1[1] / al, l1[2] / pl]
    sol = problem.solution
    exact_shock = problem.x0 + sol.right_head * info["t"]
    measured = shock_position(info["x"], info["p"], 0.5 * (sol.p_star + problem.right[2]))
    dx = info["dx"]
    print(f"{os.path.basename(args.deck)}: {len(info['x'])} cells, t = {info['t']:.6g} s after {info['step']} steps; L1 errors "
          f"rho {l1[0]:.4e} kg/m^3, u {l1[1]:.4e} m/s, p {l1[2]:.4e} Pa; shock at {measured:.5f} m (exact {exact_shock:.5f} m, "
          f"{(measured - exact_shock) / dx:+.2f} cells)")
    failures = []
    check("L1 density error / rho_L", rel[0], args.tol_density, failures)
    check("L1 velocity error / a_L (left sound speed)", rel[1], args.tol_velocity, failures)
    check("L1 pressure error / p_L", rel[2], args.tol_pressure, failures)
    check("|shock position error| (cells)", abs(measured - exact_shock) / dx, args.shock_cells, failures, "{:.2f}")
    finish("air shock tube", failures)


def two_gas(args, runner):
    extra = args.extra.split()
    opts = read_options(args.deck, extra)
    problem = Riemann(opts)
    mats = materials(opts)
    a, b = problem.left_material, problem.right_material
    with tempfile.TemporaryDirectory() as out:
        runner.run(args.deck, out, extra, args.ranks)
        l1, info = problem.errors(out, opts)
    cols, x, dx, t = info["cols"], info["x"], info["dx"], info["t"]
    sol = problem.solution
    x_contact = problem.x0 + sol.u_star * t
    theta_sum = sum(cols[f"{m}_volume_fraction"] for m in mats)
    print(f"{os.path.basename(args.deck)}: gas {a} (gamma {problem.gamma_left}) | gas {b} (gamma {problem.gamma_right}), {len(x)} cells, "
          f"t = {t:.6g} after {info['step']} steps; exact p* {sol.p_star:.6g}, u* {sol.u_star:.6g}, contact at {x_contact:.5f}")
    print(f"  L1 errors of the mixture: density {l1[0]:.4e}, velocity {l1[1]:.4e}, pressure {l1[2]:.4e}")
    failures = []
    check("L1 density error", l1[0], args.tol_density, failures)
    check("L1 velocity error", l1[1], args.tol_velocity, failures)
    check("L1 pressure error", l1[2], args.tol_pressure, failures)
    check("max |sum of volume fractions - 1|", float(np.abs(theta_sum - 1).max()), args.tol_volume_fraction, failures)
    theta_a, theta_b = cols[f"{a}_volume_fraction"], cols[f"{b}_volume_fraction"]
    right_a = x[theta_a > 0.5].max() if np.any(theta_a > 0.5) else float("-inf")
    left_b = x[theta_b > 0.5].min() if np.any(theta_b > 0.5) else float("inf")
    print(f"  gas {a} dominates (theta > 0.5) up to x = {right_a:.5f}, gas {b} from x = {left_b:.5f}; exact contact {x_contact:.5f}")
    check(f"gas {a} beyond the contact (cells; theta_{a} > 0.5 only left of contact + {args.contact_cells:g} cells)",
          max((right_a - x_contact) / dx, 0.0), args.contact_cells, failures, "{:.2f}")
    check(f"gas {b} before the contact (cells)", max((x_contact - left_b) / dx, 0.0), args.contact_cells, failures, "{:.2f}")
    # one pressure through the contact: the star region between the rarefaction tail and the shock
    lo = problem.x0 + sol.left_tail * t + args.margin_cells * dx
    hi = problem.x0 + sol.right_head * t - args.margin_cells * dx
    star = (x > lo) & (x < hi)
    dev = float(np.abs(info["p"][star] - sol.p_star).max() / sol.p_star) if np.any(star) else float("nan")
    check(f"max |p - p*|/p* in the star region [{lo:.3f}, {hi:.3f}] (through the contact)", dev, args.tol_contact_pressure, failures)
    both = (theta_a > args.presence) & (theta_b > args.presence)
    du = float(np.abs(cols[f"{a}_velocity"][both] - cols[f"{b}_velocity"][both]).max() / abs(sol.u_star)) if np.any(both) else 0.0
    print(f"  cells where both gases have theta > {args.presence:g}: {int(both.sum())}")
    check(f"max |u_{a} - u_{b}|/|u*| where both are present", du, args.tol_velocity_equal, failures)
    finish("two_gas tube", failures)


def exchange_state(cols, mats):
    """Cell-uniform state of the box: per material bulk density, T, u (means) and the spread."""
    state, spread = {}, 0.0
    for m in mats:
        vals = [cols[f"{m}_{q}"] for q in ("density", "temperature", "velocity")]
        state[m] = [float(v.mean()) for v in vals]
        for v in vals:
            spread = max(spread, float(np.ptp(v)) / max(float(np.abs(v).max()), 1e-300))
    return state, spread


def exchange_run(runner, deck, extra, steps, ranks):
    """Runs the box for 1..steps steps; returns the states after each."""
    states = []
    for n in steps:
        with tempfile.TemporaryDirectory() as out:
            runner.run(deck, out, ["-max_steps", str(n), *extra], ranks)
            t, step, cols = read_profile(out)
        states.append((step, t, *exchange_state(cols, materials(read_options(deck, extra)))))
    return states


def exchange(args, runner):
    opts = read_options(args.deck, args.extra.split())
    a, b = materials(opts)[:2]
    gamma = {m: float(opts[f"-{m}_gamma"]) for m in (a, b)}
    cv = {m: float(opts[f"-{m}_cv"]) for m in (a, b)}
    R = {m: (gamma[m] - 1) * cv[m] for m in (a, b)}
    dt = float(opts["-ice_dt"])
    H = floats(opts["-ice_exchange_heat"])[0]
    K = floats(opts["-ice_exchange_momentum"])[0]
    T0 = {m: float(opts[f"-{m}_temperature"]) for m in (a, b)}
    failures = []

    def equilibrium(rho, T):
        """Volume fractions and material densities of two ideal gases at one pressure (what the
        equilibration of the next step computes): theta_m = rho_m R_m T_m / sum(rho R T)."""
        w = {m: rho[m] * R[m] * T[m] for m in (a, b)}
        theta = {m: w[m] / (w[a] + w[b]) for m in (a, b)}
        return theta, {m: rho[m] / theta[m] for m in (a, b)}

    # 1. heat: at rest, walls (the deck)
    extra = args.extra.split()
    steps = list(range(1, args.steps + 1))
    states = exchange_run(runner, args.deck, extra, steps, args.ranks)
    rho = {m: states[0][2][m][0] for m in (a, b)}
    e0 = sum(rho[m] * cv[m] * T0[m] for m in (a, b))
    T_mean = e0 / sum(rho[m] * cv[m] for m in (a, b))
    print(f"{os.path.basename(args.deck)}: gases {a}, {b} (bulk densities {rho[a]:.6g}, {rho[b]:.6g} kg/m^3), dt {dt:g} s, H {H:g}, K {K:g}")
    print(f"  heat exchange at rest: T_{a} - T_{b} per step against the implicit closed form dT/(1 + lambda_H dt)")
    print(f"  {'step':>4} {'T_a - T_b (K)':>16} {'closed form':>16} {'lambda_H dt':>11} {'rel. error':>10}")
    T = dict(T0)
    delta = T[a] - T[b]
    worst, worst_energy, worst_spread = 0.0, 0.0, 0.0
    for step, t, state, spread in states:
        theta, rho_micro = equilibrium(rho, T)
        lam = H * (theta[b] / (rho_micro[a] * cv[a]) + theta[a] / (rho_micro[b] * cv[b]))
        predicted = delta / (1 + lam * dt)
        T = {m: state[m][1] for m in (a, b)}
        measured = T[a] - T[b]
        err = abs(measured - predicted) / abs(T0[a] - T0[b])
        print(f"  {step:4d} {measured:16.10g} {predicted:16.10g} {lam * dt:11.4f} {err:10.2e}")
        worst = max(worst, err)
        worst_energy = max(worst_energy, abs(sum(state[m][0] * cv[m] * state[m][1] for m in (a, b)) - e0) / e0)
        worst_spread = max(worst_spread, spread)
        delta = measured
    check("max |dT - closed form| / |dT_0|", worst, args.tol, failures)
    check("max relative change of sum rho c_v T", worst_energy, args.tol_conservation, failures)
    check("max spread between cells (relative; the box must stay uniform)", worst_spread, args.tol_conservation, failures)
    relaxed = exchange_run(runner, args.deck, extra, [args.relax_steps], args.ranks)[0]
    dev = max(abs(relaxed[2][m][1] - T_mean) for m in (a, b)) / T_mean
    print(f"  after {relaxed[0]} steps: T_{a} {relaxed[2][a][1]:.10g} K, T_{b} {relaxed[2][b][1]:.10g} K, mass-c_v-weighted mean {T_mean:.10g} K")
    check("max |T_m - weighted mean| / mean after relaxation", dev, args.tol, failures)

    # 2. momentum: uniform flow with different velocities through zero-gradient x faces
    va, vb = floats(args.velocities)
    dim = int(float(opts.get("-dim", "2")))
    zeros = ",0" * (dim - 1)
    extra_m = [*extra, f"-{a}_velocity", f"{va}{zeros}", f"-{b}_velocity", f"{vb}{zeros}", "-ice_bc_xmin", "outflow", "-ice_bc_xmax", "outflow"]
    states = exchange_run(runner, args.deck, extra_m, steps, args.ranks)
    rho = {m: states[0][2][m][0] for m in (a, b)}
    p0 = rho[a] * va + rho[b] * vb
    scale = rho[a] * abs(va) + rho[b] * abs(vb)
    print(f"  momentum exchange, u_{a} {va:g} and u_{b} {vb:g} m/s, outflow x faces: u_{a} - u_{b} against du/(1 + lambda_K dt)")
    print(f"  {'step':>4} {'u_a - u_b (m/s)':>16} {'closed form':>16} {'lambda_K dt':>11} {'rel. error':>10}")
    T, delta = dict(T0), va - vb
    worst, worst_momentum, worst_spread = 0.0, 0.0, 0.0
    for step, t, state, spread in states:
        theta, rho_micro = equilibrium(rho, T)
        lam = K * (theta[b] / rho_micro[a] + theta[a] / rho_micro[b])
        predicted = delta / (1 + lam * dt)
        measured = state[a][2] - state[b][2]
        err = abs(measured - predicted) / abs(va - vb)
        print(f"  {step:4d} {measured:16.10g} {predicted:16.10g} {lam * dt:11.4f} {err:10.2e}")
        worst = max(worst, err)
        worst_momentum = max(worst_momentum, abs(sum(state[m][0] * state[m][2] for m in (a, b)) - p0) / scale)
        worst_spread = max(worst_spread, spread)
        T = {m: state[m][1] for m in (a, b)}
        delta = measured
    check("max |du - closed form| / |du_0|", worst, args.tol, failures)
    check("max |change of sum rho u| / sum rho |u|", worst_momentum, args.tol_conservation, failures)
    check("max spread between cells (relative)", worst_spread, args.tol_conservation, failures)

    # 3. the drag's heat: with -ice_conservative_energy the kinetic energy the drag removes becomes
    # heat (total energy conserved); with -ice_drag_heating 0 it is dropped (thermal energy conserved,
    # the total falls by exactly the kinetic energy lost)
    def energies(state):
        thermal = sum(state[m][0] * cv[m] * state[m][1] for m in (a, b))
        kinetic = sum(0.5 * state[m][0] * state[m][2] ** 2 for m in (a, b))
        return thermal, kinetic

    thermal0 = sum(rho[m] * cv[m] * T0[m] for m in (a, b))
    kinetic0 = sum(0.5 * rho[m] * v ** 2 for m, v in ((a, va), (b, vb)))
    th_on, ke_on = energies(states[-1][2])
    off = exchange_run(runner, args.deck, [*extra_m, "-ice_drag_heating", "0"], [steps[-1]], args.ranks)[0]
    th_off, ke_off = energies(off[2])
    lost = kinetic0 - ke_off
    print(f"  drag heat after {steps[-1]} steps: kinetic energy lost {lost:.6g} J/m^3 of {kinetic0:.6g}; thermal energy change "
          f"{th_on - thermal0:.6g} (drag heating on), {th_off - thermal0:.6g} (off)")
    check("on: |change of total energy| / kinetic energy lost", abs(th_on + ke_on - thermal0 - kinetic0) / lost, args.tol_conservation, failures)
    check("off: |change of thermal energy| / kinetic energy lost", abs(th_off - thermal0) / lost, args.tol_conservation, failures)
    # the two checks above are empty unless the drag removed a real share of the kinetic energy (0.14 here)
    check_min("share of the kinetic energy the drag removed", lost / kinetic0, 1e-3, failures, "{:.3g}")
    finish("exchange", failures)


def parallel(args, runner):
    extra = ["-grid_cells", f"{args.cells},1", "-ice_advection_order", str(args.order), *args.extra.split()]
    failures = []
    with tempfile.TemporaryDirectory() as out1, tempfile.TemporaryDirectory() as out2:
        runner.run(args.deck, out1, extra, 1)
        runner.run(args.deck, out2, extra, args.ranks)
        t1, s1, c1 = read_profile(out1)
        t2, s2, c2 = read_profile(out2)
    print(f"parallel {os.path.basename(args.deck)}: {len(c1['x'])} cells, 1 rank: t = {t1:.10g} after {s1} steps; {args.ranks} ranks: t = {t2:.10g} after {s2} steps")
    same = s1 == s2 and set(c1) == set(c2) and len(c1["x"]) == len(c2["x"])
    print(f"  same steps, columns and cells: {'OK' if same else 'FAIL'}")
    if not same:
        finish("parallel", ["layout"])
    check("time difference (relative)", abs(t1 - t2) / t1, args.tol, failures)
    for k in c1:
        scale = max(float(np.abs(c1[k]).max()), 1e-300)
        check(f"max {k} difference / max |{k}|", float(np.abs(c1[k] - c2[k]).max()) / scale, args.tol, failures)
    finish(f"parallel[{os.path.basename(args.deck)}]", failures)


def conservation(args, runner):
    extra = args.extra.split()
    failures = []
    with tempfile.TemporaryDirectory() as out:
        s = runner.run(args.deck, out, extra, args.ranks)
        m = read_monitor(out)
    mass, ke, E = m["gas_mass"], m["gas_kinetic_energy"], m["gas_total_energy"]
    P = np.array([m.get(f"gas_momentum_{d}", np.zeros_like(mass)) for d in "xyz"])
    # the momentum scale sum |rho u| V is bounded by sqrt(2 M KE) (Cauchy-Schwarz); its maximum over the run
    scale = float(np.sqrt(2 * mass * ke).max())
    print(f"{os.path.basename(args.deck)}: {len(mass)} monitor rows to t = {m['time'][-1]:.6g} (step {int(m['step'][-1])}); mass {mass[0]:.10g}, "
          f"total energy {E[0]:.10g} -> {E[-1]:.10g} (internal {m['gas_internal_energy'][-1]:.6g}, kinetic {ke[-1]:.6g}); "
          f"momentum scale sqrt(2 M KE) {scale:.4g}; summary mass_change {s.get('gas', {}).get('mass_change', float('nan')):.2e}")
    check("max |mass - mass_0| / mass_0", float(np.abs(mass - mass[0]).max() / mass[0]), args.mass_tol, failures)
    check("max |momentum| / momentum scale", float(np.abs(P).max()) / max(scale, 1e-300), args.momentum_tol, failures)
    drift = (E[-1] - E[0]) / E[0]
    print(f"  total energy (burst's conservative energy form and total-energy remap conserve it to round-off;"
          f" with -ice_conservative_energy 0 -ice_advect_total_energy 0, the reference's form, it drifts): change {drift:+.3e}, "
          f"worst {float(np.abs(E - E[0]).max() / E[0]):.3e}")
    check("|total energy change| / E_0", abs(drift), args.energy_tol, failures)
    check("max |total energy - E_0| / E_0 over the run", float(np.abs(E - E[0]).max() / E[0]), args.energy_tol, failures)
    check_min("kinetic energy at the end / E_0 (the blast ran)", float(ke[-1] / E[0]), args.min_kinetic, failures, "{:.3e}")
    finish(f"conservation[{os.path.basename(args.deck)}]", failures)


# ---------------------------------------------------------------------------------------------
# Smooth problems: the acoustic pulse (explicit against semi-implicit pressure) and the low-Mach
# entropy spot (the semi-implicit pressure beyond the acoustic time-step limit)

def ideal_gas_state(opts, m):
    """(p0, c, R) of material m's uniform initial state (ideal gas)."""
    gamma, cv = float(opts[f"-{m}_gamma"]), float(opts[f"-{m}_cv"])
    R = (gamma - 1) * cv
    rho, T = float(opts[f"-{m}_density"]), float(opts[f"-{m}_temperature"])
    return rho * R * T, math.sqrt(gamma * R * T), R


def gaussian(x, opts):
    x0 = floats(opts["-ice_perturbation_center"])[0]
    w = float(opts["-ice_perturbation_width"])
    return lambda shift: np.exp(-0.5 * ((x - x0 - shift) / w) ** 2)


def norms(e, scale):
    """(max, L2 = root mean square) of e / scale."""
    return float(np.abs(e).max() / scale), float(np.sqrt(np.mean(e ** 2)) / scale)


def acoustic(args, runner):
    """Isentropic Gaussian pulse (tests/decks/acoustic_pulse.opts) with explicit and semi-implicit
    pressure at the same -ice_dt: the two paths against each other and against linear acoustics."""
    cells = [int(c) for c in args.cells.split(",")]
    base = read_options(args.deck, args.extra.split())
    mat = materials(base)[0]
    p0, c, _ = ideal_gas_state(base, mat)
    A = float(base["-ice_perturbation_amplitude"])
    lower, upper = floats(base["-grid_lower"])[0], floats(base["-grid_upper"])[0]
    t_target = float(base["-final_time"])
    scale = A * p0
    print(f"acoustic pulse ({os.path.basename(args.deck)}): p0 {p0:.6g} Pa, c {c:.6g} m/s, amplitude {A:g} p0; "
          f"acoustic Courant number c dt/h = {args.courant:g}; norms relative to the amplitude A p0")
    print(f"  {'cells':>6} {'steps':>6} {'t':>10} | {'diff max':>9} {'diff L2':>9} | {'expl max':>9} {'expl L2':>9} | "
          f"{'semi max':>9} {'semi L2':>9} | {'KSP/solve':>9}")
    rows = []
    for n in cells:
        h = (upper - lower) / n
        dt = args.courant * h / c
        steps = max(1, round(t_target / dt))
        extra = ["-grid_cells", f"{n},1", "-grid_upper", f"{upper!r},{h!r}", "-ice_dt", repr(dt), "-final_time", repr(steps * dt),
                 "-max_steps", str(steps), *args.extra.split()]
        prof, ksp = {}, 0.0
        for solver in ("explicit", "semi_implicit"):
            with tempfile.TemporaryDirectory() as out:
                s = runner.run(args.deck, out, extra + ["-ice_pressure_solver", solver])
                t, step, cols = read_profile(out)
            if solver == "semi_implicit":
                ksp = s.get("gas", {}).get("ksp_iterations_per_solve", float("nan"))
            prof[solver] = (t, step, cols)
        t, step, cols = prof["explicit"]
        x = cols["x"]
        g = gaussian(x, base)
        exact = 0.5 * scale * (g(c * t) + g(-c * t))
        pe = cols["pressure"] - p0
        ps = prof["semi_implicit"][2]["pressure"] - p0
        r = dict(n=n, diff=norms(pe - ps, scale), expl=norms(pe - exact, scale), semi=norms(ps - exact, scale), t=t, steps=step)
        rows.append(r)
        print(f"  {n:6d} {step:6d} {t:10.4e} | {r['diff'][0]:9.3e} {r['diff'][1]:9.3e} | {r['expl'][0]:9.3e} {r['expl'][1]:9.3e} | "
              f"{r['semi'][0]:9.3e} {r['semi'][1]:9.3e} | {ksp:9.2f}")
    failures = []
    # Agreement. Both paths are consistent discretisations of the same equations at the same dt;
    # they differ only in whether the face velocities that drive the pressure change see p^n or
    # p^{n+1}, an O(dt) change of a term that is itself O(dt), so their difference is a small part
    # of the error each makes against the exact solution (measured: diff/error 0.038 max and 0.044
    # L2 on 200 cells, 0.022 and 0.025 on 400). The tolerance, diff <= 0.1 x the smaller of the two
    # paths' own errors, leaves a margin of at least 2.3 on the coarse grid and still fails if a
    # path loses a term (that changes the answer by the order of the signal, not of the error).
    for r in rows:
        for k, label in ((0, "max"), (1, "L2")):
            own = min(r["expl"][k], r["semi"][k])
            check(f"{r['n']} cells: {label} |p_explicit - p_semi| / {label} error of the better path", r["diff"][k] / own, args.tol_agree, failures)
    # Convergence: both paths' errors fall under refinement (measured factor 1.85-1.88 from 200 to
    # 400 cells: the van Leer limiter clips the smooth extremum, so about first order in the max
    # norm), and the difference between the paths falls too (factor 3.2).
    for a, b in zip(rows, rows[1:]):
        for path in ("expl", "semi"):
            for k, label in ((0, "max"), (1, "L2")):
                check_min(f"{path} {label} error ratio {a['n']} -> {b['n']} cells", a[path][k] / b[path][k], args.min_ratio, failures)
        check_min(f"difference (max) ratio {a['n']} -> {b['n']} cells", a["diff"][0] / b["diff"][0], args.min_ratio, failures)
    for path in ("expl", "semi"):
        check(f"{path} max error on {rows[-1]['n']} cells / amplitude", rows[-1][path][0], args.max_error, failures)
    finish(f"acoustic[{os.path.basename(args.deck)}]", failures)


def low_mach(args, runner):
    """Entropy spot at Mach 0.003 (tests/decks/low_mach_spot.opts): semi-implicit at -ice_dt many
    times the acoustic limit is stable and accurate; explicit at the same dt fails."""
    extra = args.extra.split()
    opts = read_options(args.deck, extra)
    mat = materials(opts)[0]
    p0, c, _ = ideal_gas_state(opts, mat)
    T0 = float(opts[f"-{mat}_temperature"])
    u0 = floats(opts[f"-{mat}_velocity"])[0]
    A = float(opts["-ice_perturbation_amplitude"])
    lower, upper = floats(opts["-grid_lower"])[0], floats(opts["-grid_upper"])[0]
    n = int(opts["-grid_cells"].split(",")[0])
    h = (upper - lower) / n
    dt = float(opts["-ice_dt"])
    dt_acoustic = h / (c + abs(u0))
    print(f"low-Mach entropy spot ({os.path.basename(args.deck)}): {n} cells, u {u0:g} m/s, c {c:.6g} m/s (Mach {u0 / c:.2g}); "
          f"dt {dt:g} s = {dt / dt_acoustic:.1f} x the explicit acoustic limit h/(c+|u|) = {dt_acoustic:.4g} s; "
          f"advective Courant number u dt/h = {u0 * dt / h:.3g}")
    failures = []
    check_min("dt / acoustic limit", dt / dt_acoustic, args.min_acoustic_ratio, failures, "{:.1f}")
    check("advective Courant number u dt/h", u0 * dt / h, 0.5, failures, "{:.3f}")

    def measure(out):
        t, step, cols = read_profile(out)
        x = cols["x"]
        exact_T = T0 * (1 + A * gaussian(x, opts)(u0 * t))
        T, p, u = cols[f"{mat}_temperature"], cols["pressure"], cols[f"{mat}_velocity"]
        return dict(t=t, step=step, spot=norms(T - exact_T, A * T0), p=float(np.abs(p - p0).max() / p0),
                    u=float(np.abs(u - u0).max() / abs(u0)), finite=bool(np.all(np.isfinite(np.concatenate([T, p, u])))))

    runs = {}
    for label, more in (("semi_implicit", ["-ice_pressure_solver", "semi_implicit"]),
                        ("explicit at acoustic Courant 0.5", ["-ice_pressure_solver", "explicit", "-ice_dt", repr(0.5 * dt_acoustic),
                                                             "-monitor_interval", "10000"])):
        if label.startswith("explicit") and args.skip_reference:
            continue
        with tempfile.TemporaryDirectory() as out:
            t0 = time.perf_counter()
            s = runner.run(args.deck, out, extra + more)
            wall = time.perf_counter() - t0
            r = measure(out)
        r.update(wall=wall, ksp=s.get("gas", {}).get("ksp_iterations_per_solve", float("nan")))
        runs[label] = r
    print(f"  {'run':<34} {'steps':>6} {'wall s':>7} {'KSP/solve':>9} {'spot max':>9} {'spot L2':>9} {'max|p-p0|/p0':>12} {'max|u-u0|/u0':>12}")
    for label, r in runs.items():
        print(f"  {label:<34} {r['step']:6d} {r['wall']:7.2f} {r['ksp']:9.2f} {r['spot'][0]:9.3e} {r['spot'][1]:9.3e} {r['p']:12.3e} {r['u']:12.3e}")
    semi = runs["semi_implicit"]
    check_min("semi-implicit: all fields finite (1 = yes)", float(semi["finite"]), 1, failures, "{:.0f}")
    check("semi-implicit: max |p - p0| / p0", semi["p"], args.tol_pressure, failures)
    check("semi-implicit: max |u - u0| / u0", semi["u"], args.tol_velocity, failures)
    check("semi-implicit: max spot temperature error / amplitude", semi["spot"][0], args.tol_spot, failures)
    if "explicit at acoustic Courant 0.5" in runs:
        ref = runs["explicit at acoustic Courant 0.5"]
        check("semi-implicit spot max error / explicit-at-the-acoustic-limit error", semi["spot"][0] / ref["spot"][0], args.tol_vs_explicit, failures)
    # the explicit pressure at the same dt: it must stop with an error or blow up
    with tempfile.TemporaryDirectory() as out:
        ok, s, message = runner.try_run(args.deck, out, extra + ["-ice_pressure_solver", "explicit"])
        if ok:
            r = measure(out)
            blew_up = not r["finite"] or r["p"] > 1e-2 or r["spot"][0] > 1
            how = f"ran to the end: max |p - p0|/p0 {r['p']:.3e}, spot error {r['spot'][0]:.3e}"
        else:
            blew_up, how = True, f"stopped with an error: {message}"
    print(f"  explicit pressure at the same dt {dt:g} s: {how}")
    print(f"  explicit at the same dt fails or blows up (expected): {'OK' if blew_up else 'FAIL'}")
    if not blew_up:
        failures.append("explicit at the same dt was stable")
    finish(f"low_mach[{os.path.basename(args.deck)}]", failures)


# ---------------------------------------------------------------------------------------------
# Self-check: the same subcommands against a built-in model instead of burst

def _fv_solve(left, right, gamma, x0, lower, upper, n, t_end, cfl, order):
    """A reference finite-volume scheme for the self-check: HLL fluxes, walls, first order (donor
    cell, forward Euler) or second order (minmod-limited linear reconstruction, Heun)."""
    dx = (upper - lower) / n
    x = lower + (np.arange(n) + 0.5) * dx
    W = np.where((x < x0)[:, None], np.array(left)[None, :], np.array(right)[None, :])
    U = np.stack([W[:, 0], W[:, 0] * W[:, 1], W[:, 2] / (gamma - 1) + 0.5 * W[:, 0] * W[:, 1] ** 2], axis=1)

    def primitive(U):
        r = U[:, 0]
        u = U[:, 1] / r
        return r, u, (gamma - 1) * (U[:, 2] - 0.5 * r * u * u)

    def flux(U):
        r, u, p = primitive(U)
        return np.stack([r * u, r * u * u + p, u * (U[:, 2] + p)], axis=1), u, np.sqrt(gamma * p / r)

    def rate(U):
        G = np.concatenate([U[1::-1], U, U[:-3:-1]])  # two mirrored ghosts each side
        G[:2, 1] *= -1
        G[-2:, 1] *= -1
        if order == 1:
            UL, UR = G[1:n + 2], G[2:n + 3]
        else:
            d1, d2 = G[1:-1] - G[:-2], G[2:] - G[1:-1]
            s = np.where(d1 * d2 > 0, np.sign(d1) * np.minimum(np.abs(d1), np.abs(d2)), 0.0)
            UL, UR = G[1:n + 2] + 0.5 * s[:n + 1], G[2:n + 3] - 0.5 * s[1:n + 2]
        FL, uL, aL = flux(UL)
        FR, uR, aR = flux(UR)
        SL = np.minimum(uL - aL, uR - aR)[:, None]
        SR = np.maximum(uL + aL, uR + aR)[:, None]
        F = np.where(SL >= 0, FL, np.where(SR <= 0, FR, (SR * FL - SL * FR + SL * SR * (UR - UL)) / (SR - SL)))
        return -(F[1:] - F[:-1]) / dx

    t, steps = 0.0, 0
    while t < t_end * (1 - 1e-14):
        r, u, p = primitive(U)
        dt = min(cfl * dx / float(np.max(np.abs(u) + np.sqrt(gamma * p / r))), t_end - t)
        if order == 1:
            U = U + dt * rate(U)
        else:
            U1 = U + dt * rate(U)
            U = 0.5 * (U + U1 + dt * rate(U1))
        t += dt
        steps += 1
    r, u, p = primitive(U)
    return x, r, u, p, t, steps


def _write_profile(out, t, step, x, p, fields):
    """fields: [(material, density, velocity, temperature, volume_fraction)]"""
    with open(os.path.join(out, "profile.csv"), "w") as f:
        f.write(f"# time {t!r} step {step}\n")
        f.write(",".join(["x", "pressure"] + [f"{m}_{q}" for m, *_ in fields for q in ("density", "velocity", "temperature", "volume_fraction")]) + "\n")
        for k in range(len(x)):
            f.write(",".join(repr(float(v)) for v in [x[k], p[k]] + [c[k] for _, *cs in fields for c in cs]) + "\n")


class Synthetic:
    """Writes what burst would write, from models with known answers: a reference finite-volume
    scheme for one gas, exact cell averages for two gases, the implicit closed form for the
    exchange box and an exactly symmetric budget for the closed box. `fault` injects an error that
    a check must catch: 'explicit_exchange', 'shifted_shock', 'mixed_gases', 'energy_leak'."""

    def __init__(self, fault=None):
        self.fault = fault

    def run(self, deck, out, extra=(), ranks=1):
        o = read_options(deck, extra)
        mats = materials(o)
        cells = [int(c) for c in o["-grid_cells"].split(",")]
        steps = 0
        if o.get("-ice_perturbation", "none") != "none":
            steps = self._smooth(o, out, mats, cells[0])
        elif "-ice_uniform_volume_fraction" in o:
            steps = self._exchange(o, out, mats, cells[0])
        elif o.get("-ice_riemann_shape", "planar") != "planar":
            steps = self._box(o, out)
        elif len(set([o.get("-ice_riemann_left_material", mats[0]), o.get("-ice_riemann_right_material", mats[0])])) == 2:
            steps = self._two_gas(o, out, mats, cells[0])
        else:
            steps = self._tube(o, out, mats, cells[0])
        with open(os.path.join(out, "summary.json"), "w") as f:
            json.dump({"steps": steps, "particles": 0, "gas": {"mass": 1.0, "total_energy": 1.0, "mass_change": 0.0, "momentum": [0, 0, 0]}}, f)
        return {"steps": steps, "gas": {"mass_change": 0.0}}

    def try_run(self, deck, out, extra=(), ranks=1):
        o = read_options(deck, extra)
        if o.get("-ice_perturbation") == "entropy" and o.get("-ice_pressure_solver") == "explicit" and self.fault != "stable_explicit":
            p0, c, _ = ideal_gas_state(o, materials(o)[0])
            n = int(o["-grid_cells"].split(",")[0])
            h = (floats(o["-grid_upper"])[0] - floats(o["-grid_lower"])[0]) / n
            if float(o["-ice_dt"]) > h / c:
                return False, None, "synthetic: the explicit pressure beyond the acoustic limit"
        return True, self.run(deck, out, extra, ranks), ""

    def _smooth(self, o, out, mats, n):
        """The acoustic pulse and the entropy spot: the exact answer with a smooth O(h) error (and an
        O(h^2) difference between the pressure paths); faults 'acoustic_mismatch', 'stable_explicit'."""
        m = mats[0]
        p0, c, R = ideal_gas_state(o, m)
        T0 = float(o[f"-{m}_temperature"])
        A = float(o["-ice_perturbation_amplitude"])
        lower, upper = floats(o["-grid_lower"])[0], floats(o["-grid_upper"])[0]
        h = (upper - lower) / n
        x = lower + (np.arange(n) + 0.5) * h
        t = float(o["-final_time"])
        g = gaussian(x, o)
        ones = np.ones(n)
        if o["-ice_perturbation"] == "acoustic":
            damp = 1 - 8 * h
            if o.get("-ice_pressure_solver") == "semi_implicit":
                damp -= 0.1 if self.fault == "acoustic_mismatch" else 20 * h * h
            p = p0 + 0.5 * A * p0 * damp * (g(c * t) + g(-c * t))
            T = T0 * (p / p0) ** (0.4 / 1.4)
            _write_profile(out, t, 100, x, p, [(m, p / (R * T), 0 * ones, T, ones)])
        else:
            u0 = floats(o[f"-{m}_velocity"])[0]
            T = T0 * (1 + 0.98 * A * g(u0 * t))
            _write_profile(out, t, 100, x, p0 * ones, [(m, p0 / (R * T), u0 * ones, T, ones)])
        return 100

    def _tube(self, o, out, mats, n):
        pr = Riemann(o)
        gamma, cv = pr.gamma_left, float(o[f"-{mats[0]}_cv"])
        x, r, u, p, t, steps = _fv_solve(pr.left, pr.right, gamma, pr.x0, pr.lower, pr.upper, n, float(o["-final_time"]),
                                         float(o.get("-ice_cfl", 0.25)), int(o.get("-ice_advection_order", 2)))
        if self.fault == "shifted_shock":
            shift = 3
            r, u, p = (np.concatenate([f[:1].repeat(shift), f[:-shift]]) for f in (r, u, p))
        _write_profile(out, t, steps, x, p, [(mats[0], r, u, p / (r * (gamma - 1) * cv), np.ones_like(r))])
        return steps

    def _two_gas(self, o, out, mats, n):
        pr = Riemann(o)
        t = float(o["-final_time"])
        dx = (pr.upper - pr.lower) / n
        x = pr.lower + (np.arange(n) + 0.5) * dx
        r, u, p = pr.averages(x, t)
        xc = pr.x0 + pr.solution.u_star * t
        theta_a = np.clip((xc - (x - 0.5 * dx)) / dx, 1e-12, 1 - 1e-12)
        if self.fault == "mixed_gases":
            theta_a = np.clip(theta_a + 0.6 * (np.abs(x - xc) < 6 * dx), 1e-12, 1 - 1e-12)
        fields = []
        for m, theta in ((pr.left_material, theta_a), (pr.right_material, 1 - theta_a)):
            R = (float(o[f"-{m}_gamma"]) - 1) * float(o[f"-{m}_cv"])
            fields.append((m, theta * r, u, p / (r * R), theta))
        _write_profile(out, t, 100, x, p, fields)
        return 100

    def _exchange(self, o, out, mats, n):
        a, b = mats[:2]
        cv = {m: float(o[f"-{m}_cv"]) for m in (a, b)}
        R = {m: (float(o[f"-{m}_gamma"]) - 1) * cv[m] for m in (a, b)}
        theta0 = floats(o["-ice_uniform_volume_fraction"])
        rho = {m: th * float(o[f"-{m}_density"]) for m, th in zip((a, b), theta0)}
        T = {m: float(o[f"-{m}_temperature"]) for m in (a, b)}
        u = {m: floats(o[f"-{m}_velocity"])[0] for m in (a, b)}
        dt, H, K = float(o["-ice_dt"]), floats(o["-ice_exchange_heat"])[0], floats(o["-ice_exchange_momentum"])[0]
        steps = int(o["-max_steps"])
        for _ in range(steps):
            w = {m: rho[m] * R[m] * T[m] for m in (a, b)}
            th = {m: w[m] / (w[a] + w[b]) for m in (a, b)}
            v = {m: th[m] / rho[m] for m in (a, b)}  # specific volumes 1/rho_micro
            # per-material betas as in ice.md 1.8, then the 2 x 2 implicit solve
            bT = {a: dt * th[b] * H * v[a] / cv[a], b: dt * th[a] * H * v[b] / cv[b]}
            bU = {a: dt * th[b] * K * v[a], b: dt * th[a] * K * v[b]}
            # burst's order: momentum, the drag's heat (one temperature rise; off with
            # -ice_drag_heating 0), then heat
            kinetic = sum(0.5 * rho[m] * u[m] ** 2 for m in (a, b))
            for q, beta in ((u, bU), (T, bT)):
                if self.fault == "explicit_exchange":
                    q[a], q[b] = q[a] + beta[a] * (q[b] - q[a]), q[b] + beta[b] * (q[a] - q[b])
                else:
                    E = np.array([[1 + beta[a], -beta[a]], [-beta[b], 1 + beta[b]]])
                    q[a], q[b] = np.linalg.solve(E, [q[a], q[b]])
                if q is u and o.get("-ice_drag_heating", "1").lower() not in ("0", "false", "no"):
                    rise = (kinetic - sum(0.5 * rho[m] * u[m] ** 2 for m in (a, b))) / sum(rho[m] * cv[m] for m in (a, b))
                    for m in (a, b):
                        T[m] += max(rise, 0.0)
        dx = (floats(o["-grid_upper"])[0] - floats(o["-grid_lower"])[0]) / n
        x = (np.arange(n) + 0.5) * dx
        w = {m: rho[m] * R[m] * T[m] for m in (a, b)}
        ones = np.ones(n)
        _write_profile(out, steps * dt, steps, x, (w[a] + w[b]) * ones,
                       [(m, rho[m] * ones, u[m] * ones, T[m] * ones, w[m] / (w[a] + w[b]) * ones) for m in (a, b)])
        return steps

    def _box(self, o, out):
        steps = 60
        t = np.linspace(0, float(o["-final_time"]), steps + 1)
        rng = np.random.default_rng(1)
        mass = np.full_like(t, 0.9 * 4)
        ke = 0.3 * (1 - np.exp(-t / 0.05))
        E = 3.2 * (1 + (0.05 if self.fault == "energy_leak" else 1e-3) * t / t[-1])
        with open(os.path.join(out, "monitor.csv"), "w") as f:
            w = csv.writer(f)
            w.writerow(["step", "time", "gas_mass", "gas_momentum_x", "gas_momentum_y", "gas_momentum_z", "gas_internal_energy",
                        "gas_kinetic_energy", "gas_total_energy", "ice_ksp_iterations"])
            for k in range(len(t)):
                w.writerow([k, repr(t[k]), repr(mass[k] * (1 + 1e-16 * rng.standard_normal())), repr(1e-16 * rng.standard_normal()),
                            repr(1e-16 * rng.standard_normal()), 0.0, repr(E[k] - ke[k]), repr(ke[k]), repr(E[k]), 0])
        return steps


def self_check(args, _runner):
    """Runs the checks against Synthetic (no burst) and reports whether each passes or fails as it should."""
    results = []

    def expect(label, argv, fault=None, should_pass=True):
        print(f"\n=== self-check: {label} (must {'pass' if should_pass else 'FAIL'}) ===")
        sub = make_parser().parse_args(["--synthetic", *argv])
        try:
            COMMANDS[sub.cmd](sub, Synthetic(fault))
            code = 0
        except SystemExit as e:
            code = e.code if isinstance(e.code, int) else 1
        ok = (code == 0) == should_pass
        results.append((label, ok))

    # the error computation itself: an exact cell-averaged profile has zero error, and a profile
    # sampled at the cell centres differs from it only in the cells the waves cross
    print("=== self-check: L1 errors of exact profiles ===")
    opts = read_options(SOD)
    problem = Riemann(opts)
    with tempfile.TemporaryDirectory() as out:
        x = (np.arange(400) + 0.5) / 400
        for label, (r, u, p) in (("cell averages", problem.averages(x, 0.2)),
                                 ("centre samples", riemann_exact.sample(x, 0.2, problem.left, problem.right, 1.4, 1.4, 0.5))):
            _write_profile(out, 0.2, 1, x, p, [("gas", r, u, p / (r * 287.0), np.ones_like(r))])
            l1, _ = problem.errors(out, opts)
            print(f"  {label}: L1 errors {l1[0]:.2e} {l1[1]:.2e} {l1[2]:.2e}")
            if label == "cell averages":
                results.append(("exact averages give zero error", max(l1) < 1e-15))
            else:
                # at most (total variation, here < 1) x dx
                results.append(("centre samples differ by less than TV dx", 0 < max(l1) < 1.0 / 400))
    orders = observed_orders([100, 200, 400], [0.04, 0.02, 0.01])
    results.append(("observed order of a halving error is 1", max(abs(o - 1) for o in orders) < 1e-14))

    expect("sod, first order, HLL reference scheme", ["sod", "--order", "1"])
    expect("sod, second order, and second beats first", ["sod", "--order", "2", "--compare-orders"])
    expect("air shock tube", ["air"])
    expect("air shock tube, shock displaced 3 cells", ["air"], fault="shifted_shock", should_pass=False)
    expect("two gases, exact profile", ["two_gas"])
    expect("two gases, gas a smeared beyond the contact", ["two_gas"], fault="mixed_gases", should_pass=False)
    expect("exchange, implicit closed form", ["exchange"])
    expect("exchange, explicit update", ["exchange"], fault="explicit_exchange", should_pass=False)
    expect("parallel", ["parallel"])
    expect("conservation", ["conservation"])
    expect("conservation, energy leaking 5 %", ["conservation"], fault="energy_leak", should_pass=False)
    expect("acoustic pulse", ["acoustic"])
    expect("acoustic pulse, semi-implicit path off by 10 % of the amplitude", ["acoustic"], fault="acoustic_mismatch", should_pass=False)
    expect("low-Mach spot", ["low_mach"])
    expect("low-Mach spot, explicit stable beyond the acoustic limit", ["low_mach"], fault="stable_explicit", should_pass=False)
    print("\n=== self-check summary ===")
    for label, ok in results:
        print(f"  {label}: {'OK' if ok else 'FAIL'}")
    finish("verify_ice self-check", [label for label, ok in results if not ok])


# ---------------------------------------------------------------------------------------------

COMMANDS = {"sod": sod, "air": air, "two_gas": two_gas, "exchange": exchange, "parallel": parallel, "conservation": conservation,
            "acoustic": acoustic, "low_mach": low_mach, "overshoot": overshoot, "t123": toro123, "self_check": self_check}


def make_parser():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", help="the burst executable")
    p.add_argument("--synthetic", action="store_true", help="run the checks against the built-in reference model instead of burst")
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("sod", help="Sod tube: L1 errors and observed orders")
    s.add_argument("--deck", default=SOD)
    s.add_argument("--order", type=int, choices=(1, 2), default=2)
    s.add_argument("--cells", default="100,200,400,800")
    s.add_argument("--min-order-density", type=float, default=None, help="default 0.6 (order 1), 0.7 (order 2)")
    s.add_argument("--min-order-velocity", type=float, default=None, help="default as density")
    s.add_argument("--min-order-pressure", type=float, default=None, help="default as density")
    s.add_argument("--max-l1", type=float, default=None, help="finest-grid L1 density error; default 0.02 (order 1), 0.01 (order 2)")
    s.add_argument("--compare-orders", action="store_true", help="also run the other order; second order must have smaller errors")
    s.add_argument("--ranks", type=int, default=1)
    s.add_argument("--extra", default="")
    a = sub.add_parser("air", help="dimensional air tube against the exact solution")
    a.add_argument("--deck", default="options/scenes/shock_tube_air.opts")
    a.add_argument("--tol-density", type=float, default=0.02)
    a.add_argument("--tol-velocity", type=float, default=0.02)
    a.add_argument("--tol-pressure", type=float, default=0.02)
    a.add_argument("--shock-cells", type=float, default=2.0)
    a.add_argument("--ranks", type=int, default=1)
    a.add_argument("--extra", default="")
    t = sub.add_parser("two_gas", help="two gases with different gammas")
    t.add_argument("--deck", default="tests/decks/two_gas_tube.opts")
    t.add_argument("--tol-density", type=float, default=0.02)
    t.add_argument("--tol-velocity", type=float, default=0.03)
    t.add_argument("--tol-pressure", type=float, default=0.02)
    t.add_argument("--tol-volume-fraction", type=float, default=1e-8, help="max |sum theta - 1| in profile.csv")
    t.add_argument("--contact-cells", type=float, default=3.0, help="gas a may dominate up to this many cells past the exact contact")
    t.add_argument("--margin-cells", type=float, default=4.0, help="cells left out next to the rarefaction tail and the shock")
    # measured 3.3e-2: the pressure blip where two gases of different gamma meet, the contact error of
    # every mixture (volume-fraction) scheme (Abgrall 1996); a single gas shows none. The band is set
    # a priori at 5 %, not from the measurement; it fails if the contact treatment gets worse (5.1e-2
    # was seen with a mixed energy form that was then dropped).
    t.add_argument("--tol-contact-pressure", type=float, default=0.05, help="max |p - p*|/p* in the star region")
    t.add_argument("--presence", type=float, default=0.01, help="volume fraction above which a gas counts as present")
    t.add_argument("--tol-velocity-equal", type=float, default=0.01, help="max |u_a - u_b|/|u*| where both are present")
    t.add_argument("--ranks", type=int, default=1)
    t.add_argument("--extra", default="")
    e = sub.add_parser("exchange", help="uniform two-gas box against the implicit exchange closed form")
    e.add_argument("--deck", default="tests/decks/exchange_box.opts")
    e.add_argument("--steps", type=int, default=5)
    e.add_argument("--relax-steps", type=int, default=120)
    e.add_argument("--velocities", default="100,-50", help="u_a,u_b (m/s) of the momentum run")
    e.add_argument("--tol", type=float, default=1e-9)
    e.add_argument("--tol-conservation", type=float, default=1e-12)
    e.add_argument("--ranks", type=int, default=1)
    e.add_argument("--extra", default="")
    q = sub.add_parser("parallel", help="1 rank against several: profile.csv agrees")
    q.add_argument("--deck", default=SOD)
    q.add_argument("--cells", type=int, default=200)
    q.add_argument("--order", type=int, default=2)
    q.add_argument("--ranks", type=int, default=2)
    q.add_argument("--tol", type=float, default=1e-12)
    q.add_argument("--extra", default="")
    c = sub.add_parser("conservation", help="closed-box blast: mass, momentum, energy")
    c.add_argument("--deck", default="tests/decks/closed_box.opts")
    c.add_argument("--mass-tol", type=float, default=1e-12)
    c.add_argument("--momentum-tol", type=float, default=1e-10)
    c.add_argument("--energy-tol", type=float, default=1e-2)
    c.add_argument("--min-kinetic", type=float, default=1e-3)
    c.add_argument("--ranks", type=int, default=1)
    c.add_argument("--extra", default="")
    ac = sub.add_parser("acoustic", help="acoustic pulse: explicit and semi-implicit pressure agree and converge")
    ac.add_argument("--deck", default="tests/decks/acoustic_pulse.opts")
    ac.add_argument("--cells", default="200,400")
    ac.add_argument("--courant", type=float, default=0.3, help="acoustic Courant number c dt/h of the fixed -ice_dt")
    ac.add_argument("--tol-agree", type=float, default=0.1, help="max (and L2) path difference / the smaller path error")
    ac.add_argument("--min-ratio", type=float, default=1.5, help="least error reduction factor per grid doubling")
    ac.add_argument("--max-error", type=float, default=0.05, help="finest-grid max error / amplitude")
    ac.add_argument("--extra", default="")
    lm = sub.add_parser("low_mach", help="low-Mach entropy spot: semi-implicit beyond the acoustic limit")
    lm.add_argument("--deck", default="tests/decks/low_mach_spot.opts")
    lm.add_argument("--min-acoustic-ratio", type=float, default=5.0, help="least dt / (h/(c+|u|)) of the deck")
    lm.add_argument("--tol-pressure", type=float, default=1e-6, help="max |p - p0|/p0")
    lm.add_argument("--tol-velocity", type=float, default=1e-4, help="max |u - u0|/u0")
    lm.add_argument("--tol-spot", type=float, default=0.05, help="max temperature error / spot amplitude")
    lm.add_argument("--tol-vs-explicit", type=float, default=1.25, help="semi-implicit spot error / explicit (at acoustic Courant 0.5) error")
    lm.add_argument("--skip-reference", action="store_true", help="skip the explicit run at the acoustic limit (40000 steps)")
    lm.add_argument("--extra", default="")
    o = sub.add_parser("overshoot", help="pressure overshoot and dip behind shocks (Sod, Mach 3, ratio 1e5)")
    o.add_argument("--cases", default="sod,mach3,ratio1e5")
    o.add_argument("--cells", default="", help="grids (comma-separated); default per case")
    o.add_argument("--tol", type=float, default=0.03, help="largest overshoot and dip, as a fraction of the shock's pressure jump")
    o.add_argument("--extra", default="")
    t3 = sub.add_parser("t123", help="Toro's 123 problem: the near-vacuum star state converges")
    t3.add_argument("--cells", default="400,800,1600")
    t3.add_argument("--tol-pressure", type=float, default=0.1, help="star pressure error on the finest grid")
    t3.add_argument("--tol-velocity", type=float, default=0.03, help="max |u| in the star region's inner half on the finest grid (exact 0)")
    t3.add_argument("--min-order", type=float, default=0.8)
    t3.add_argument("--extra", default="")
    sub.add_parser("self_check", help="check this script against a built-in model (no burst needed)")
    return p


def main():
    args = make_parser().parse_args()
    if args.cmd == "self_check" or args.synthetic:
        runner = Synthetic()
    elif args.burst:
        runner = Burst(args.burst)
    else:
        raise SystemExit("--burst is required (or --synthetic)")
    COMMANDS[args.cmd](args, runner)


if __name__ == "__main__":
    main()
