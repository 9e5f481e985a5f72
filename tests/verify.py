#!/usr/bin/python3
"""Verification drivers for burst: each subcommand runs real option files through the burst
executable, compares the output with an analytic answer, prints the measured figures with a
verdict, and exits non-zero on failure. ctest calls them (tests/CMakeLists.txt).

  bar          axial bar vibration, period and tip amplitude (verification.md 1.1)
  convergence  axis-aligned manufactured solution, error at three resolutions and observed order
               (--axisymmetric: the axisymmetric radial/axial one, tests/decks/mms_axisymmetric.opts)
               (Wallstedt & Guilkey 2008; verification.md 1.3)
  disks        colliding elastic disks, energy drift with FLIP and PIC (Sulsky 1994; verification.md 1.2)
  parallel     the same deck on 1 and 2 ranks: particle count, positions and energies agree
  deck         an option file runs a few steps and writes its summary
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]


def run(burst, deck, out, extra=(), ranks=1):
    cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [burst, "-options_file", deck, "-output_dir", out, "-progress", "false", *extra]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-4000:])
        sys.stdout.write(proc.stderr[-4000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def monitor(out):
    with open(os.path.join(out, "monitor.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def check(name, value, tol, failures, fmt="{:.3e}"):
    ok = value <= tol
    print(f"  {name}: " + fmt.format(value) + f" (tol {tol:g}) {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append(name)


def finish(test, failures):
    if failures:
        print(f"{test}: FAIL ({', '.join(failures)})")
        sys.exit(1)
    print(f"{test}: OK")


def bar(args):
    """Period from the upward zero crossings of the tip displacement; amplitude from its extremes."""
    deck = os.path.join(ROOT, "tests/decks/bar_vibration.opts")
    length, v0, E, rho = 25.0, 0.1, 100.0, 1.0
    omega = math.pi / (2 * length) * math.sqrt(E / rho)
    failures, errors = [], []
    for cells_along in (15, 30):
        h = length / cells_along
        cells_x = int(round(30.0 / h))
        ppc = 2
        # the tip particle: last particle of the first row (pids run x fastest in each cell, cells x fastest)
        tip = (cells_along - 1) * ppc * ppc + (ppc - 1)
        with tempfile.TemporaryDirectory() as out:
            run(args.burst, deck, out, ["-mpm_shape_type", args.shape, "-grid_upper", f"{cells_x * h},{h}", "-grid_cells", f"{cells_x},1",
                                        "-rod_upper", f"{length},{h}", "-monitor_track_pid", str(tip), "-final_time", "30"])
            m = monitor(out)
        t, u = m["time"], m["track_ux"]
        X = m["track_x"][0]
        crossings = []
        for k in range(1, len(t)):
            if u[k - 1] < 0 <= u[k]:
                crossings.append(t[k - 1] + (t[k] - t[k - 1]) * (-u[k - 1]) / (u[k] - u[k - 1]))
        period = np.mean(np.diff(crossings)) if len(crossings) >= 2 else float("nan")
        amplitude = 0.5 * (u.max() - u.min())
        exact_period = 2 * math.pi / omega
        exact_amplitude = v0 / omega * math.sin(math.pi * X / (2 * length))
        e_period = abs(period - exact_period) / exact_period
        e_amp = abs(amplitude - exact_amplitude) / exact_amplitude
        drift = abs(m["balance_error"][-1])
        print(f"bar_vibration {args.shape}, {cells_along} cells: period {period:.5f} s (exact {exact_period:.5f}), "
              f"tip amplitude {amplitude:.5f} m (exact {exact_amplitude:.5f} at X = {X:.4f} m), energy drift {drift:.2e}")
        check("period relative error", e_period, args.tol_period, failures)
        check("amplitude relative error", e_amp, args.tol_amplitude, failures)
        errors.append(e_period + e_amp)
    ok = errors[1] < errors[0]
    print(f"  combined error falls with refinement: {errors[0]:.3e} -> {errors[1]:.3e} {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("refinement")
    finish(f"bar_vibration[{args.shape}]", failures)


# The spatial order the manufactured solutions should show (Wallstedt & Guilkey 2008, the axis-aligned
# solution): the smooth-gradient weights (uGIMP, cpGIMP, quadratic B-spline) converge at second
# order; linear weights do not converge (the cell-crossing error grows as particles cross faces).
SMOOTH_SHAPE_ORDER = {"ugimp": 2.0, "cpgimp": 2.0, "bspline2": 2.0}
# Default margin below the theoretical order: the time error and the pre-asymptotic coarse pair pull
# the observed finest-pair order off 2 (measured 1.93-2.32 over the registered cases, dt 1e-5 / 2e-5;
# README Verification), so 0.3 below the theory holds all of them and still fails an order-1 method.
ORDER_MARGIN = 0.3
# Linear weights stall: the finest-pair order measured 0.43 (2-D, 8/16/32 cells); a linear run
# that converged at first order or better would mean the cell-crossing error is no longer seen.
LINEAR_MAX_ORDER = 1.0


def convergence_bounds(args):
    """The bound every convergence run checks: the one given, or the one its shape's theory implies.
    A run without any bound would check nothing, so there is always one."""
    if args.min_order is not None or args.max_order is not None or args.max_error is not None:
        args.bound_reason = "bound given by the caller"
        return
    if args.shape in SMOOTH_SHAPE_ORDER:
        args.min_order = SMOOTH_SHAPE_ORDER[args.shape] - ORDER_MARGIN
        args.bound_reason = f"theoretical order {SMOOTH_SHAPE_ORDER[args.shape]:g} less the margin {ORDER_MARGIN:g}"
    elif args.shape == "linear":
        args.max_order = LINEAR_MAX_ORDER
        args.bound_reason = "linear weights stall"
    else:
        raise SystemExit(f"FAIL: convergence: no order known for shape {args.shape}; give --min-order, --max-order or --max-error")


def convergence(args):
    convergence_bounds(args)
    deck = os.path.join(ROOT, "tests/decks/mms_axisymmetric.opts" if args.axisymmetric else "tests/decks/mms_axis_aligned.opts")
    cells = [int(c) for c in args.cells.split(",")]
    errors = []
    for n in cells:
        extra = ["-mpm_shape_type", args.shape, "-mpm_scheme", args.scheme]
        if args.dim == 3:
            extra += ["-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", f"{n},{n},{n}", "-square_lower", "0,0,0",
                      "-square_upper", "1,1,1", "-bc_zmin", "symmetry", "-bc_zmax", "symmetry"]
        else:
            extra += ["-grid_cells", f"{n},{n}"]
        if args.f_update:
            extra += ["-mpm_F_update", args.f_update]
        if args.dt:
            extra += ["-mpm_dt", args.dt]
        with tempfile.TemporaryDirectory() as out:
            s = run(args.burst, deck, out, extra)
        errors.append(s["displacement_error_rms"])
    name = f"convergence[{'axisymmetric' if args.axisymmetric else str(args.dim) + 'd'},{args.shape},{args.scheme}]"
    if not all(math.isfinite(e) and e > 0 for e in errors):
        print(f"  rms displacement errors {errors}: not finite and positive")
        finish(name, ["errors"])
    orders = [math.log(errors[k] / errors[k + 1]) / math.log(cells[k + 1] / cells[k]) for k in range(len(cells) - 1)]
    print(f"{'mms_axisymmetric' if args.axisymmetric else 'mms_axis_aligned'} {args.dim}-D {args.shape} {args.scheme} F update {args.f_update or 'linear'}: cells {cells}, rms displacement error "
          + ", ".join(f"{e:.3e}" for e in errors) + " m; observed order " + ", ".join(f"{o:.2f}" for o in orders))
    failures = []
    if args.min_order is not None:
        ok = orders[-1] >= args.min_order
        print(f"  finest observed order {orders[-1]:.2f} >= {args.min_order} ({args.bound_reason}) {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append("order")
    if args.max_order is not None:
        ok = orders[-1] <= args.max_order
        print(f"  finest observed order {orders[-1]:.2f} <= {args.max_order} (stalls: cell-crossing error) {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append("stall")
    if args.max_error is not None:
        check("finest rms error (m)", errors[-1], args.max_error, failures)
    finish(name, failures)


def disks(args):
    deck = os.path.join(ROOT, "options/scenes/colliding_disks.opts")
    failures = []
    results = {}
    for label, flip in (("FLIP", "1"), ("PIC", "0")):
        with tempfile.TemporaryDirectory() as out:
            s = run(args.burst, deck, out, ["-mpm_flip_fraction", flip, "-mpm_scheme", args.scheme, "-output_interval", "0", "-output_grid", "false"])
            m = monitor(out)
        e0 = m["total"][0] - m["external_work"][0]
        drift = (m["total"][-1] - m["external_work"][-1] - e0) / e0
        worst = np.max(np.abs(m["total"] - m["external_work"] - e0)) / e0
        momentum = max(abs(s["momentum"][0]), abs(s["momentum"][1])) / (s["mass"] * 0.1)
        results[label] = drift
        print(f"colliding_disks {label} {args.scheme}: initial energy {e0:.4f} J/m, final drift {drift:+.3e}, worst {worst:.3e}, "
              f"kinetic at t_end {m['kinetic'][-1]:.4f} J/m, |momentum|/(M v0) {momentum:.1e}")
        check(f"{label} momentum (relative)", momentum, 1e-10, failures)
    check("FLIP energy drift |dE/E0|", abs(results["FLIP"]), args.tol_flip, failures)
    ok = results["PIC"] < -args.pic_loss
    print(f"  PIC dissipates: drift {results['PIC']:+.3e} < -{args.pic_loss} {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("PIC dissipation")
    finish(f"colliding_disks[{args.scheme}]", failures)


def loads(args):
    """Resultant of the pressure on a quarter ring = p R_i per metre in x and y: with free faces the
    total momentum changes by dt times the resultant each step. Gravity: M g."""
    failures = []
    deck = os.path.join(ROOT, "tests/decks/pressurized_ring.opts")
    inner_radius = 0.0508
    with tempfile.TemporaryDirectory() as out:
        run(args.burst, deck, out, ["-max_steps", "40"])
        m = monitor(out)
    # the pressure at t_n acts over [t_n, t_n+1]; ramp p(t) = 1e13 t
    t, px, py = m["time"], m["momentum_x"], m["momentum_y"]
    impulse = np.sum(1e13 * np.minimum(t[:-1], 1e-5) * np.diff(t)) * inner_radius
    ex, ey = abs(px[-1] - impulse) / impulse, abs(py[-1] - impulse) / impulse
    print(f"pressurized_ring: momentum after {len(t) - 1} steps ({px[-1]:.6e}, {py[-1]:.6e}) N s/m, impulse of p R_i {impulse:.6e} N s/m")
    check("x resultant error (relative)", ex, args.tol, failures)
    check("y resultant error (relative)", ey, args.tol, failures)
    with tempfile.TemporaryDirectory() as out:
        s = run(args.burst, os.path.join(ROOT, "tests/decks/bench_block.opts"), out,
                ["-gravity", "0,-9.81", "-block_velocity", "0,0", "-max_steps", "50", "-steel_youngs_modulus", "1e6", "-mpm_scheme", "musl"])
        m = monitor(out)
    expected = -9.81 * s["final_time"] * s["mass"]
    e = abs(s["momentum"][1] - expected) / abs(expected)
    print(f"gravity: momentum_y {s['momentum'][1]:.9e} after t = {s['final_time']:.4e} s, expected M g t = {expected:.9e}")
    check("gravity momentum error (relative)", e, 1e-10, failures)
    work = m["external_work"][-1]
    ke = m["kinetic"][-1] + m["internal"][-1]
    check("gravity: work = kinetic + internal energy (relative)", abs(work - ke) / abs(work), 1e-3, failures)
    finish("loads", failures)


def plate_impact(args):
    """Uniaxial-strain plate impact on a rigid wall (tests/decks/plate_impact.opts): arrival time of
    the elastic precursor and of the plastic wave at a traced particle, the HEL plateau between them,
    and the final stress sigma_HEL + rho c_p (v - u_HEL) (models.md 7.6)."""
    E, nu, rho, s0, H, v = 200e9, 0.3, 7800.0, 300e6, 2e9, 50.0
    G, K = E / (2 * (1 + nu)), E / (3 * (1 - 2 * nu))
    M = K + 4 * G / 3
    c_l = math.sqrt(M / rho)
    hel = s0 * M / (2 * G)
    c_p = math.sqrt((K + 4.0 / 3.0 * G * H / (H + 3 * G)) / rho)
    u_hel = hel / (rho * c_l)
    final = hel + rho * c_p * (v - u_hel)
    failures = []
    with tempfile.TemporaryDirectory() as out:
        # h = 0.125 mm along x; the traced particle starts at x = 20.03 mm
        run(args.burst, os.path.join(ROOT, args.deck), out, ["-grid_cells", args.cells, "-monitor_track_point", "0.02003125,0.0000625,0.0000625",
                                                             "-final_time", "6e-6", *args.extra.split()])
        m = monitor(out)
    t, sxx, x0 = m["time"], -m["track_sxx"], m["track_x"][0]

    def arrival(level):
        k = np.argmax(sxx >= level)
        return t[k - 1] + (t[k] - t[k - 1]) * (level - sxx[k - 1]) / (sxx[k] - sxx[k - 1])

    t_elastic = arrival(0.5 * hel)
    t_plastic = arrival(0.5 * (hel + final))
    window = (t > t_elastic + 0.25 * (t_plastic - t_elastic)) & (t < t_elastic + 0.75 * (t_plastic - t_elastic))
    # Without damping the front rings (dispersion of the discrete wave, about +-10 % here), so the
    # plateau is the median over the middle half between the two fronts, with the spread printed.
    plateau = np.median(sxx[window])
    spread = (sxx[window].max() - sxx[window].min()) / (2 * hel)
    late = t > t_plastic + 0.6e-6
    final_measured = sxx[late].mean()
    print(f"{os.path.basename(args.deck)}: plate impact at {v} m/s, particle at x = {1e3 * x0:.3f} mm: precursor speed {x0 / t_elastic:.1f} m/s (exact {c_l:.1f}), "
          f"plastic wave {x0 / t_plastic:.1f} m/s (exact {c_p:.1f}), HEL plateau {plateau / 1e6:.1f} MPa (exact {hel / 1e6:.1f}; ringing +-{100 * spread:.0f} %), "
          f"final stress {final_measured / 1e6:.1f} MPa (exact {final / 1e6:.1f})")
    check("precursor speed relative error", abs(x0 / t_elastic - c_l) / c_l, 0.02, failures)
    check("plastic wave speed relative error", abs(x0 / t_plastic - c_p) / c_p, 0.03, failures)
    check("HEL plateau relative error", abs(plateau - hel) / hel, 0.03, failures)
    check("final stress relative error", abs(final_measured - final) / final, 0.03, failures)
    finish("plate_impact", failures)


def fragments(args):
    """The fragment finder on separate bodies: the count, and each fragment's mass and centroid
    against the seeded bodies (the centroid of a disk is its centre), on 1 or 2 ranks."""
    failures = []
    with tempfile.TemporaryDirectory() as out:
        s = run(args.burst, os.path.join(ROOT, args.deck), out, ["-fragments", *args.extra.split()], ranks=args.ranks)
        with open(os.path.join(out, "fragments.csv")) as f:
            rows = list(csv.DictReader(f))
    centroids = sorted((round(float(r["centroid_x"]), 6), round(float(r["centroid_y"]), 6), round(float(r["centroid_z"]), 6)) for r in rows)
    expected = sorted(tuple(float(v) for v in c.split(",")) for c in args.centroids.split(";"))
    print(f"fragments of {os.path.basename(args.deck)} on {args.ranks} rank(s): {s['fragment_count']} (expected {len(expected)}), "
          f"masses {[round(float(r['mass']), 4) for r in rows]} kg, intact mass {s['intact_mass']:.4f} of {s['mass']:.4f} kg")
    ok = s["fragment_count"] == len(expected) and len(rows) == len(expected)
    print(f"  count: {'OK' if ok else 'FAIL'}")
    if not ok:
        finish("fragments", ["count"])
    err = max(max(abs(a - b) for a, b in zip(c, e)) for c, e in zip(centroids, expected))
    check("max centroid error (m)", err, args.tol, failures)
    check("intact mass - total mass (relative)", abs(s["intact_mass"] - s["mass"]) / s["mass"], 1e-12, failures)
    finish("fragments", failures)


def grady(args):
    """Validation report (paper eqs. 25-26 and its 6-7 fragments on the quarter): runs a fragmenting
    scene and prints its fragment count beside the Grady-Hightower band for the measured expansion
    velocity at the first failure. Fragment counts in the softening regime depend on the mesh, so
    this fails only on a gross mismatch (outside [shear/2, 3 x tension]) or a broken energy balance."""
    with tempfile.TemporaryDirectory() as out:
        s = run(args.burst, os.path.join(ROOT, args.deck), out, ["-output_interval", "0", *args.extra.split()], ranks=args.ranks)
    n = s["fragment_count"]
    lo, hi = s["grady_shear"]["sector"], s["grady_tension"]["sector"]
    print(f"{s['scene']} ({s['cells'][0]} x {s['cells'][1]} cells, {s['particles']} particles, {s['ranks']} rank(s)): {n} fragments of at least "
          f"{s['fragment_min_particles']} particles; Grady-Hightower for V = {s['fracture_velocity']:.1f} m/s at t = {1e6 * s['fracture_time']:.1f} us: "
          f"{lo:.2f} (shear) to {hi:.2f} (tension) on the modelled sector; the paper reports 6-7 on the quarter; "
          f"energy balance error {s['energy_balance_error']:.2e}, failure energy {s['failure_energy']:.3g} J/m")
    failures = []
    ok = 0.5 * lo <= n <= 3 * hi
    print(f"  count within [shear/2, 3 x tension] = [{0.5 * lo:.2f}, {3 * hi:.2f}]: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("count")
    check("|energy balance error|", abs(s["energy_balance_error"]), 0.02, failures)
    finish(f"grady[{s['scene']}] (validation report)", failures)


def contact(args):
    """Contact between velocity fields (tests/decks/sliding_block.opts): frictionless contact keeps the
    slider's horizontal velocity (the normals at the block's corners are not exactly vertical: 2e-3),
    Coulomb friction slows it, and in no case does the slider sink into the base."""
    failures = []
    results = {}
    for label, extra in (("frictionless", []), ("friction 0.5", ["-mpm_contact_friction", "0.5"])):
        with tempfile.TemporaryDirectory() as out:
            run(args.burst, os.path.join(ROOT, "tests/decks/sliding_block.opts"), out, ["-output_interval", "0", *extra])
            with h5py.File(sorted(os.path.join(out, f) for f in os.listdir(out) if f.startswith("particles_"))[-1], "r") as f:
                g = f["particles"]
                mat, v, m, x = g["material"][...].ravel(), g["velocity"][...], g["mass"][...].ravel(), g["coordinates"][...]
            slider = mat == 1
            vx = (m[slider] * v[slider, 0]).sum() / m[slider].sum()
            gap = x[slider, 1].min() - x[~slider, 1].max()
            results[label] = vx
            print(f"sliding block, {label}: slider velocity {vx:.6f} m/s (started at 1), gap between the blocks {1e3 * gap:.2f} mm")
            check(f"{label}: interpenetration (m)", max(-gap, 0.0), 0.0, failures)
    check("frictionless: |v_x - 1| (m/s)", abs(results["frictionless"] - 1), 2e-3, failures)
    ok = results["friction 0.5"] < 0.9
    print(f"  friction slows the slider: {results['friction 0.5']:.3f} < 0.9 {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("friction")
    finish("contact", failures)


def xpic(args):
    """XPIC(m) on the colliding disks (Hammerquist & Nairn 2017): XPIC(1) is PIC to rounding; as m grows
    the energy lost falls monotonically from PIC's towards FLIP's, and momentum stays zero."""
    deck = os.path.join(ROOT, "options/scenes/colliding_disks.opts")
    failures, finals = [], {}
    runs = [("FLIP", ["-mpm_flip_fraction", "1"]), ("PIC", ["-mpm_flip_fraction", "0"])]
    runs += [(f"XPIC({m})", ["-mpm_transfer", "xpic", "-mpm_xpic_order", str(m)]) for m in args.orders]
    histories = {}
    for label, opts in runs:
        with tempfile.TemporaryDirectory() as out:
            s = run(args.burst, deck, out, [*opts, "-mpm_scheme", args.scheme, "-output_interval", "0", "-output_grid", "false"])
            m = monitor(out)
        e0 = m["total"][0] - m["external_work"][0]
        histories[label] = m["total"] - m["external_work"]
        finals[label] = (m["total"][-1] - m["external_work"][-1] - e0) / e0
        momentum = max(abs(s["momentum"][0]), abs(s["momentum"][1])) / (s["mass"] * 0.1)
        print(f"colliding_disks {label} {args.scheme}: final energy change {finals[label]:+.4e}, |momentum|/(M v0) {momentum:.1e}")
        check(f"{label} momentum (relative)", momentum, 1e-10, failures)
    same = np.abs(histories["XPIC(1)"] - histories["PIC"]).max() / histories["PIC"][0] if "XPIC(1)" in histories else 0
    check("XPIC(1) energy history against PIC (relative)", same, 1e-10, failures)
    chain = ["PIC"] + [f"XPIC({m})" for m in args.orders if m > 1] + ["FLIP"]
    ok = all(finals[a] < finals[b] for a, b in zip(chain, chain[1:]))
    print("  energy change rises monotonically " + " < ".join(f"{c} {finals[c]:+.3e}" for c in chain) + f": {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("monotone in m")
    finish(f"xpic[{args.scheme}]", failures)


def rotation(args):
    """Rigid rotation through the transfers (tests/decks/spinning_disk.opts): a force-free spinning disk
    whose exact motion keeps every particle's velocity (free flight), so the kinetic energy and the
    angular momentum about the centre stay constant. (1) one transfer round trip (one step of 1e-9 s):
    APIC returns omega x (x - c) to rounding, PIC does not; (2) 1000 steps of 1e-3 s: PIC loses the
    spin; APIC keeps kinetic energy and angular momentum up to an error that does not depend on dt
    (measured: 2.852e-2, 2.868e-2, 2.877e-2 at dt 1e-3, 5e-4, 2.5e-4) but falls as h^2 (2.85e-2,
    7.5e-3, 1.9e-3 on 20, 40, 80 cells): at the rim of the disk the lumped nodal mass centre is not the
    node, and the particle velocity that moved with the particle carries that into the next P2G. The
    check: both drifts below --tol-drift on 20 cells and falling at order >= 1.6 to 40 cells."""
    deck = os.path.join(ROOT, "tests/decks/spinning_disk.opts")
    failures = []
    omega, centre, radius = 1.0, np.array([0.5, 0.5]), 0.2

    def load(out, first):
        files = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".h5"))
        with h5py.File(os.path.join(out, files[0 if first else -1]), "r") as f:
            g = f["particles"]
            order = np.argsort(g["id"][...].ravel())
            return {k: g[k][...][order] for k in ("coordinates", "velocity", "mass")}

    def angular(p):
        r = p["coordinates"][:, :2] - centre
        v = p["velocity"][:, :2]
        return float(np.sum(p["mass"].ravel() * (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0])))

    results = {}
    for label, opts in (("APIC", ["-mpm_transfer", "apic"]), ("PIC", ["-mpm_transfer", "flip_pic", "-mpm_flip_fraction", "0"])):
        extra = ["-mpm_shape_type", args.shape, *opts]
        with tempfile.TemporaryDirectory() as out:
            run(args.burst, deck, out, extra + ["-max_steps", "1", "-mpm_dt", "1e-9", "-output_interval", "1"])
            p0, p1 = load(out, True), load(out, False)
        r0 = p0["coordinates"][:, :2] - centre
        exact = omega * np.stack([-r0[:, 1], r0[:, 0]], axis=1)
        round_trip = np.abs(p1["velocity"][:, :2] - exact).max() / (omega * radius)
        drifts = []
        for cells in ((20, 40) if label == "APIC" else (20,)):
            with tempfile.TemporaryDirectory() as out:
                run(args.burst, deck, out, extra + ["-grid_cells", f"{cells},{cells}"])
                m = monitor(out)
                q0, q1 = load(out, True), load(out, False)
            drifts.append((m["kinetic"][-1] / m["kinetic"][0] - 1, angular(q1) / angular(q0) - 1))
        ke, lz = drifts[0]
        results[label] = (round_trip, ke, lz, drifts)
        print(f"rotation {label} {args.shape}: one round trip max |v - omega x r|/(omega R) {round_trip:.2e}; after 1000 steps kinetic energy "
              + ", ".join(f"{d[0]:+.3e}" for d in drifts) + ", angular momentum " + ", ".join(f"{d[1]:+.3e}" for d in drifts) + " (relative; 20" + (", 40" if len(drifts) > 1 else "") + " cells)")
    a, p = results["APIC"], results["PIC"]
    check("APIC round trip error", a[0], args.tol_round_trip, failures)
    check("APIC kinetic energy change |dK/K0|", abs(a[1]), args.tol_drift, failures)
    check("APIC angular momentum change |dL/L0|", abs(a[2]), args.tol_drift, failures)
    (k20, l20), (k40, l40) = a[3]
    order = min(math.log2(abs(k20 / k40)), math.log2(abs(l20 / l40)))
    ok = order >= 1.6
    print(f"  APIC drifts fall with h at order {order:.2f} >= 1.6: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("APIC drift order")
    ok = p[0] > 100 * args.tol_round_trip and p[2] < -0.5
    print(f"  PIC is not exact (round trip {p[0]:.1e}) and loses the spin (angular momentum {p[2]:+.2f}): {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("PIC control")
    finish(f"rotation[{args.shape}]", failures)


def read_particles(out):
    files = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".h5"))
    with h5py.File(os.path.join(out, files[-1]), "r") as f:
        g = f["particles"]
        order = np.argsort(g["id"][...].ravel())
        return {k: g[k][...][order] for k in ("id", "coordinates", "velocity", "stress", "temperature", "porosity", "plastic_strain", "damage") if k in g}


def parallel(args):
    deck = os.path.join(ROOT, args.deck)
    extra = ["-max_steps", str(args.steps), "-output_interval", "0", *args.extra.split()]
    failures = []
    with tempfile.TemporaryDirectory() as out1, tempfile.TemporaryDirectory() as out2:
        s1 = run(args.burst, deck, out1, extra)
        s2 = run(args.burst, deck, out2, extra, ranks=2)
        p1, p2 = read_particles(out1), read_particles(out2)
    print(f"parallel {os.path.basename(args.deck)}: {s1['particles']} particles on 1 rank, {s2['particles']} on 2 ranks after {s1['steps']} steps")
    same_ids = p1["id"].shape == p2["id"].shape and np.array_equal(p1["id"], p2["id"])
    print(f"  particle count and ids conserved: {'OK' if same_ids and s1['particles'] == s2['particles'] else 'FAIL'}")
    if not (same_ids and s1["particles"] == s2["particles"]):
        finish("parallel", ["count"])
    size = np.ptp(p1["coordinates"], axis=0).max()
    dx = np.abs(p1["coordinates"] - p2["coordinates"]).max() / size
    vscale = max(np.abs(p1["velocity"]).max(), 1e-300)
    dv = np.abs(p1["velocity"] - p2["velocity"]).max() / vscale
    sscale = max(np.abs(p1["stress"]).max(), 1e-300)
    ds = np.abs(p1["stress"] - p2["stress"]).max() / sscale
    de = abs(s1["kinetic_energy"] - s2["kinetic_energy"]) / max(s1["kinetic_energy"], 1e-300)
    check("max position difference / body size", dx, args.tol, failures)
    check("max velocity difference / max velocity", dv, args.tol, failures)
    check("max stress difference / max stress", ds, args.tol, failures)
    check("kinetic energy difference (relative)", de, args.tol, failures)
    for key in ("temperature", "porosity", "plastic_strain", "damage"):
        if key in p1:
            scale = max(np.abs(p1[key]).max(), 1e-300)
            check(f"max {key} difference (relative to its max {scale:.3g})", np.abs(p1[key] - p2[key]).max() / scale, args.tol, failures)
    if args.phases:
        # each rank's phase times (summary.json, with -log_view): every phase on both ranks, none
        # negative, the particle phases busy on both, and the disjoint phases (ghost_sums runs inside
        # p2g and remap) adding up to no more than the rank's stepping wall time
        phases = s2.get("rank_phase_seconds", {})
        names = ["p2g", "ghost_sums", "grid_update", "g2p", "remap", "stress", "migrate", "time_step", "stepping"]
        shaped = all(len(phases.get(n, [])) == 2 and min(phases[n]) >= 0 for n in names)
        print(f"  rank_phase_seconds: {phases}")
        check("rank_phase_seconds missing, mis-shaped or negative (0 = OK)", 0 if shaped else 1, 0, failures, fmt="{:.0f}")
        if shaped:
            busy = min(min(phases[n]) for n in ("p2g", "g2p", "stress", "stepping"))
            check("particle phases without time on a rank (0 = OK)", 0 if busy > 0 else 1, 0, failures, fmt="{:.0f}")
            disjoint = [sum(phases[n][r] for n in names[:-1] if n != "ghost_sums") / phases["stepping"][r] for r in range(2)]
            check("largest share of the stepping time in the disjoint phases, minus 1 (<= 0 = OK)", max(disjoint) - 1, 0, failures)
    finish(f"parallel[{os.path.basename(args.deck)}]", failures)


def deck(args):
    """A deck runs: particles (with their XDMF output) if it has any, gas mass if it has an ICE gas
    (summary.json "gas"), and at least one of the two."""
    with tempfile.TemporaryDirectory() as out:
        s = run(args.burst, os.path.join(ROOT, args.deck), out, ["-max_steps", str(args.steps), *args.extra.split()], ranks=args.ranks)
        particles = s.get("particles", 0)
        particles_ok = particles == 0 or os.path.exists(os.path.join(out, "particles.xmf"))
        gas_mass = s.get("gas", {}).get("mass", 0.0)
        ok = s["steps"] >= 1 and (particles > 0 or gas_mass > 0) and particles_ok
    energy = s.get("energy_balance_error")
    print(f"deck {args.deck} on {args.ranks} rank(s): {s['steps']} steps, {particles} particles, gas mass {gas_mass:.6g}"
          + (f", energy balance error {energy:.2e}" if energy is not None else "") + f" {'OK' if ok else 'FAIL'}")
    sys.exit(0 if ok else 1)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    sub = p.add_subparsers(dest="cmd", required=True)
    b = sub.add_parser("bar")
    b.add_argument("--shape", default="linear")
    b.add_argument("--tol-period", type=float, default=5e-3)
    b.add_argument("--tol-amplitude", type=float, default=5e-3)
    c = sub.add_parser("convergence")
    c.add_argument("--shape", default="cpgimp")
    c.add_argument("--scheme", default="usl")
    c.add_argument("--dim", type=int, default=2)
    c.add_argument("--cells", default="8,16,32")
    c.add_argument("--dt", default=None)
    c.add_argument("--f-update", default=None)
    c.add_argument("--min-order", type=float, default=None, help="fail if the finest pair's observed order is below this "
                   "(default, when no bound is given: the shape's theoretical order less %g)" % ORDER_MARGIN)
    c.add_argument("--max-order", type=float, default=None, help="fail if the finest pair's observed order is above this "
                   "(default for linear weights, which stall: %g)" % LINEAR_MAX_ORDER)
    c.add_argument("--max-error", type=float, default=None, help="fail if the finest rms displacement error (m) is above this")
    c.add_argument("--axisymmetric", action="store_true", help="the axisymmetric manufactured solution (tests/decks/mms_axisymmetric.opts)")
    d = sub.add_parser("disks")
    d.add_argument("--scheme", default="musl")
    d.add_argument("--tol-flip", type=float, default=5e-3)
    d.add_argument("--pic-loss", type=float, default=0.05)
    q = sub.add_parser("parallel")
    q.add_argument("--deck", required=True)
    q.add_argument("--steps", type=int, default=50)
    q.add_argument("--tol", type=float, default=1e-10)
    q.add_argument("--extra", default="")
    q.add_argument("--phases", action="store_true", help="also check the 2-rank run's rank_phase_seconds (pass -log_view in --extra)")
    ld = sub.add_parser("loads")
    ld.add_argument("--tol", type=float, default=2e-2)
    pi = sub.add_parser("plate_impact")
    pi.add_argument("--deck", default="tests/decks/plate_impact.opts")
    pi.add_argument("--cells", default="400,1,1")
    pi.add_argument("--extra", default="")
    fr = sub.add_parser("fragments")
    fr.add_argument("--deck", default="tests/decks/three_bodies.opts")
    fr.add_argument("--ranks", type=int, default=1)
    fr.add_argument("--centroids", default="0.25,0.25,0;0.7,0.3,0;0.5,0.725,0")
    fr.add_argument("--tol", type=float, default=1e-3)
    fr.add_argument("--extra", default="")
    sub.add_parser("contact")
    gr = sub.add_parser("grady")
    gr.add_argument("--deck", default="options/scenes/ring2d.opts")
    gr.add_argument("--ranks", type=int, default=1)
    gr.add_argument("--extra", default="")
    xp = sub.add_parser("xpic")
    xp.add_argument("--scheme", default="musl")
    xp.add_argument("--orders", type=lambda t: [int(v) for v in t.split(",")], default=[1, 2, 5])
    ro = sub.add_parser("rotation")
    ro.add_argument("--shape", default="bspline2")
    ro.add_argument("--tol-round-trip", type=float, default=1e-12)
    ro.add_argument("--tol-drift", type=float, default=5e-2)
    k = sub.add_parser("deck")
    k.add_argument("--deck", required=True)
    k.add_argument("--steps", type=int, default=5)
    k.add_argument("--ranks", type=int, default=1)
    k.add_argument("--extra", default="")
    args = p.parse_args()
    {"bar": bar, "convergence": convergence, "disks": disks, "parallel": parallel, "deck": deck, "loads": loads, "plate_impact": plate_impact, "fragments": fragments, "grady": grady, "contact": contact, "rotation": rotation, "xpic": xpic}[args.cmd](args)


if __name__ == "__main__":
    main()
