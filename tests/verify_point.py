#!/usr/bin/python3
"""Verification of the metal-model layer through the material-point driver (burst -mode point).
Each subcommand runs the driver, compares with a closed form, prints the measured figures with a
verdict, and exits non-zero on failure.

  simple_shear     Green-Naghdi stress against Dienes' closed form up to gamma = 10 (second order), the
                   Jaumann (linear_elastic) model against its own closed form (first order, within the
                   bound of its rotation/stretch split), neo-Hookean exact; the two rates differ:
                   Jaumann oscillates, Green-Naghdi grows monotonically (models.md 7.5)
  linear_hardening uniaxial stress with linear hardening against the closed-form stress-strain
                   curve; stress on the yield surface at every plastic step; step-size consistency
  rotation         uniaxial strain with a superposed rigid rotation: the stress after a full (and a
                   quarter) turn equals the unrotated one, converging at second order
  heating          adiabatic temperature rise equals the integral of eq. 18, chi sigma_f deps_p/(rho Cp)
  jc_4340          Johnson-Cook 4340 against the Johnson & Cook (1985) data of verification.md 5
                   (a validation report: prints the RMS error, fails only on a gross mismatch)
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METAL = os.path.join(ROOT, "tests/materials/metal_linear_hardening.opts")


def options(path):
    """The -name value pairs of an option file."""
    with open(path) as f:
        pairs = [line.split() for line in f if line.startswith("-")]
    return {p[0]: p[1] if len(p) > 1 else "" for p in pairs}


def point(burst, options, out):
    cmd = [burst, "-mode", "point", *options, "-point_output", out]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if proc.returncode:
        sys.stdout.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"FAIL: {' '.join(cmd)}")
    return np.genfromtxt(out, delimiter=",", names=True)


def check(name, value, tol, failures):
    ok = value <= tol
    print(f"  {name}: {value:.3e} (tol {tol:g}) {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append(name)


def finish(test, failures):
    print(f"{test}: {'FAIL (' + ', '.join(failures) + ')' if failures else 'OK'}")
    sys.exit(1 if failures else 0)


def green_naghdi(gamma):
    """Dienes (1979): sigma11/G and sigma12/G of a hypoelastic solid in simple shear, GN rate."""
    beta = np.arctan(gamma / 2)
    s11 = 4 * (np.cos(2 * beta) * np.log(np.cos(beta)) + beta * np.sin(2 * beta) - np.sin(beta) ** 2)
    s12 = 2 * np.cos(2 * beta) * (2 * beta - 2 * np.tan(2 * beta) * np.log(np.cos(beta)) - np.tan(beta))
    return s11, s12


def shear_runs(burst, steps, tmp, final=10.0, G=1e6):
    """Simple shear (L_xy = 1 /s) to gamma = final of three elastic solids with shear modulus G:
    elastic_plastic with an unreachable yield stress (Green-Naghdi: co-rotational with the polar R),
    linear_elastic (Jaumann, Hughes-Winget) and neo_hookean (hyperelastic). Returns the three CSVs."""
    common = ["-point_path", "simple_shear", "-point_rate", "1", "-point_final_strain", repr(final), "-point_steps", str(steps)]
    elastic = ["-metal_density", "7800", "-metal_youngs_modulus", repr(2 * G * 1.3), "-metal_poisson_ratio", "0.3"]
    gn = point(burst, ["-options_file", METAL, "-metal_flow_stress_yield_stress", "1e30", "-metal_shear_modulus", repr(G), *common], os.path.join(tmp, "gn.csv"))
    ja = point(burst, ["-materials", "metal", "-metal_model", "linear_elastic", *elastic, *common], os.path.join(tmp, "ja.csv"))
    nh = point(burst, ["-materials", "metal", "-metal_model", "neo_hookean", *elastic, *common], os.path.join(tmp, "nh.csv"))
    return gn, ja, nh


def shear_errors(gn, ja, nh, G=1e6):
    """max |sigma/G - closed form| over the path for each rate (models.md 7.5)."""
    g = gn["strain"]
    s11, s12 = green_naghdi(g)
    e_gn = max(np.abs(gn["stress_xx"] / G - s11).max(), np.abs(gn["stress_xy"] / G - s12).max(), np.abs(gn["stress_yy"] / G + s11).max())
    e_ja = max(np.abs(ja["stress_xx"] / G - (1 - np.cos(g))).max(), np.abs(ja["stress_xy"] / G - np.sin(g)).max(),
               np.abs(ja["stress_yy"] / G + (1 - np.cos(g))).max())
    # neo-Hookean, J = 1: sigma12 = G gamma, sigma11 = G gamma^2, sigma22 = 0 (relative to max(1, |exact|))
    e_nh = max((np.abs(nh["stress_xy"] / G - g) / np.maximum(1, g)).max(), (np.abs(nh["stress_xx"] / G - g ** 2) / np.maximum(1, g ** 2)).max(),
               np.abs(nh["stress_yy"] / G).max())
    return e_gn, e_ja, e_nh


def simple_shear(args):
    """Jaumann against Green-Naghdi under large rotation (models.md 7.5), to gamma = 10.
    Tolerances: the Green-Naghdi update (polar R of F, deviator integrated in the rotated frame at
    the mid-step) is second order: its error must fall at order >= 1.9 from 2000 to 4000 steps and
    stay below 1e-5 G (measured 5.2e-7; the chart resolves 1e-3). The Jaumann update
    sigma_{n+1} = Q sigma_n Q^T + dt C:D (Hughes-Winget) is exact for a pure spin but splits rotation
    and stretching: each step's local error is G dgamma^2 |[W, D]| = G dgamma^2 / 2 in simple shear, so
    the global error is bounded by G gamma dgamma / 2 (1.25e-2 G at 4000 steps; measured 2.5e-3 G) and
    falls at first order (>= 0.9 required). The neo-Hookean stress depends on F alone: exact to the
    CSV's 10 digits (1e-8 relative). The physics: Jaumann sigma12 oscillates (|sigma12| <= G, turns
    negative past gamma = pi), Green-Naghdi sigma12 grows monotonically."""
    G = 1e6
    failures = []
    errors = {}
    with tempfile.TemporaryDirectory() as tmp:
        for steps in (args.steps // 2, args.steps):
            gn, ja, nh = shear_runs(args.burst, steps, tmp, G=G)
            errors[steps] = shear_errors(gn, ja, nh, G)
    g = gn["strain"]
    s11, s12 = green_naghdi(g)
    n0, n1 = args.steps // 2, args.steps
    order = [math.log(errors[n0][k] / errors[n1][k]) / math.log(n1 / n0) for k in range(2)]
    dgamma = 10.0 / n1
    print(f"simple shear to gamma = 10 in {n1} steps: Green-Naghdi at gamma 10: s11/G {gn['stress_xx'][-1] / G:.4f} (exact {s11[-1]:.4f}), "
          f"s12/G {gn['stress_xy'][-1] / G:.4f} (exact {s12[-1]:.4f}); Jaumann s12/G {ja['stress_xy'][-1] / G:.4f} (exact {math.sin(10):.4f}); "
          f"neo-Hookean s12/G {nh['stress_xy'][-1] / G:.4f} (exact 10)")
    print(f"  max errors/G at {n0} and {n1} steps: Green-Naghdi {errors[n0][0]:.3e}, {errors[n1][0]:.3e} (order {order[0]:.2f}); "
          f"Jaumann {errors[n0][1]:.3e}, {errors[n1][1]:.3e} (order {order[1]:.2f})")
    check("elastic_plastic (Green-Naghdi) max |sigma/G - Dienes|", errors[n1][0], 1e-5, failures)
    check("Green-Naghdi order deficit 1.9 - order", 1.9 - order[0], 0, failures)
    check("linear_elastic (Jaumann) max |sigma/G - closed form|", errors[n1][1], 0.5 * 10.0 * dgamma, failures)
    check("Jaumann order deficit 0.9 - order", 0.9 - order[1], 0, failures)
    check("neo_hookean max relative |sigma/G - closed form|", errors[n1][2], 1e-8, failures)
    # the physics each rate gives: Jaumann bounded and oscillating, Green-Naghdi monotonic
    ja12, gn12 = ja["stress_xy"] / G, gn["stress_xy"] / G
    check("Jaumann: max sigma12/G - 1 (bounded by G)", ja12.max() - 1, errors[n1][1], failures)
    check("Jaumann: sigma12/G at gamma = 4 (negative past pi; exact -0.757)", ja12[np.argmin(np.abs(g - 4))] + 0.7, 0, failures)
    check("Green-Naghdi: largest decrease of sigma12 along the path (monotonic)", -np.diff(gn12).min(), 0, failures)
    differ = abs(ja12[-1] - gn12[-1])
    check("the two rates differ at gamma 10: 1 - |d s12/G|", 1 - differ, 0, failures)
    finish("simple_shear", failures)


def linear_hardening(args):
    """Uniaxial stress, E = 200 GPa, nu 0.3, sigma_0 = 300 MPa, H = 2 GPa (H = d sigma/d eps_p in
    uniaxial stress for von Mises). Small-strain closed form: sigma = E eps below eps_y = sigma_0/E,
    then sigma = sigma_0 + E_t (eps - eps_y), E_t = E H/(E + H). At finite strain the rate form
    integrates sum D dt exactly (the 'strain' column, rate x time), the strain measure compared here."""
    E, s0, H = 200e9, 300e6, 2e9
    Et = E * H / (E + H)
    failures = []
    curves = {}
    with tempfile.TemporaryDirectory() as tmp:
        for steps in (200, 400):
            curves[steps] = point(args.burst, ["-options_file", METAL, "-point_path", "uniaxial_stress", "-point_rate", "1e3", "-point_final_strain", "0.05",
                                               "-point_steps", str(steps), "-point_adiabatic", "false"], os.path.join(tmp, f"lh{steps}.csv"))
    d = curves[400]
    eps = d["strain"]
    exact = np.where(eps < s0 / E, E * eps, s0 + Et * (eps - s0 / E))
    # the step that crosses the yield point mixes elastic and plastic: compare away from it
    mask = np.abs(eps - s0 / E) > 2 * (eps[1] - eps[0])
    e_curve = np.abs(d["stress_xx"] - exact)[mask].max() / s0
    plastic = d["plastic_strain"] > 0
    e_surface = np.abs(d["von_mises"][plastic] - (s0 + H * d["plastic_strain"][plastic])).max() / s0
    e_lateral = max(np.abs(d["stress_yy"]).max(), np.abs(d["stress_zz"]).max()) / s0
    e_refine = abs(curves[200]["stress_xx"][-1] - d["stress_xx"][-1]) / d["stress_xx"][-1]
    print(f"uniaxial stress, linear hardening: final stress {d['stress_xx'][-1] / 1e6:.3f} MPa (closed form {exact[-1] / 1e6:.3f}), "
          f"plastic strain {d['plastic_strain'][-1]:.5f}")
    check("max |sigma - closed form| / sigma_0", e_curve, 1e-6, failures)
    check("max |q - sigma_f(eps_p)| / sigma_0 on plastic steps", e_surface, 1e-8, failures)
    check("max lateral stress / sigma_0", e_lateral, 1e-8, failures)
    check("final stress change 200 -> 400 steps (relative)", e_refine, 1e-6, failures)
    finish("linear_hardening", failures)


def heating(args):
    """Adiabatic: T - T0 = chi/(rho Cp) integral sigma_f d eps_p (eq. 18); hypoelastic EOS, no
    Gruneisen term. Rate-independent linear hardening: the integral is exact per step because the
    update uses sigma_f at t_{n+1} times the increment, which the trapezoid rule reproduces up to the
    difference between left and right sums; compare with both and require the model's own sum."""
    chi, rho, cp = 0.9, 7800.0, 477.0
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        d = point(args.burst, ["-options_file", METAL, "-point_path", "uniaxial_stress", "-point_rate", "1e3", "-point_final_strain", "0.3",
                               "-point_steps", "600", "-point_temperature", "300"], os.path.join(tmp, "heat.csv"))
    dT = d["temperature"] - 300.0
    deps = np.diff(d["plastic_strain"])
    density = rho / (d["F_xx"] * d["F_yy"] ** 2)  # uniaxial stress: F_zz = F_yy
    implicit = chi / cp * np.concatenate([[0], np.cumsum(d["flow_stress"][1:] * deps / density[1:])])
    s0, H = 300e6, 2e9
    exact = chi / (rho * cp) * (s0 * d["plastic_strain"] + 0.5 * H * d["plastic_strain"] ** 2)
    e_sum = np.abs(dT - implicit).max() / dT[-1]
    e_exact = abs(dT[-1] - exact[-1]) / dT[-1]
    print(f"adiabatic heating to plastic strain {d['plastic_strain'][-1]:.4f}: dT = {dT[-1]:.4f} K, "
          f"integral of eq. 18 = {exact[-1]:.4f} K (closed form for linear hardening)")
    check("|dT - sum chi sigma_f d eps_p/(rho Cp)| / dT (CSV keeps 10 digits)", e_sum, 1e-8, failures)
    check("|dT - closed-form integral| / dT", e_exact, 5e-3, failures)
    finish("heating", failures)


def rotation(args):
    """Uniaxial strain (F_xx 1 -> 1.002, elastic-plastic: sigma_0 = 100 MPa) with a superposed rigid
    rotation about z (verification.md 1.4): after a full turn, and after a quarter turn rotated back,
    the stress equals that of the unrotated path; the difference converges at second order."""
    failures = []
    base = ["-options_file", METAL, "-metal_flow_stress_yield_stress", "100e6", "-point_path", "rotating_uniaxial_strain", "-point_rate", "0.002",
            "-point_final_strain", "0.002"]
    errors = {}
    keys = ["stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_yz", "stress_xz"]
    with tempfile.TemporaryDirectory() as tmp:
        for steps in (400, 1600):
            ref = point(args.burst, base + ["-point_steps", str(steps), "-point_rotation_angle", "0"], os.path.join(tmp, "a.csv"))[-1]
            for angle in (2 * math.pi, math.pi / 2):
                d = point(args.burst, base + ["-point_steps", str(steps), "-point_rotation_angle", repr(angle)], os.path.join(tmp, "b.csv"))[-1]
                errors[(steps, angle)] = max(abs(d[k] - ref[k]) for k in keys) / abs(ref["stress_xx"])
        plastic = ref["plastic_strain"]
    for angle, label in ((2 * math.pi, "full turn"), (math.pi / 2, "quarter turn")):
        order = math.log(errors[(400, angle)] / errors[(1600, angle)]) / math.log(4)
        print(f"uniaxial strain with a superposed {label} (plastic strain {plastic:.2e}): max |sigma - sigma_unrotated| / sigma_xx = "
              f"{errors[(400, angle)]:.2e} (400 steps), {errors[(1600, angle)]:.2e} (1600 steps), observed order {order:.2f}")
        check(f"{label}, 400 steps", errors[(400, angle)], 2e-4, failures)
        ok = order >= 1.8
        print(f"  second-order convergence: order {order:.2f} >= 1.8 {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"{label} order")
    finish("rotation", failures)


def failure_response(args):
    """A point that fails on its first step (initial porosity 0.5 above the critical 0.3) then carries
    nothing (zero_stress), only its pressure (no_shear), or only a compressive pressure (no_tension);
    intact (response none) it keeps its full stress."""
    failures = []
    base = ["-options_file", METAL, "-metal_porosity_initial_mean", "0.5", "-metal_failure_porosity", "0.3", "-metal_failure_criteria", "porosity",
            "-point_rate", "100", "-point_final_strain", "0.01", "-point_steps", "50"]
    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for response in ("none", "zero_stress", "no_shear", "no_tension"):
            for path in ("uniaxial_strain", "hydrostatic"):
                sign = ["-point_velocity_gradient", "-1,0,0,0,-1,0,0,0,-1", "-point_path", "velocity_gradient"] if path == "hydrostatic" else ["-point_path", path]
                runs[(response, path)] = point(args.burst, base + ["-metal_failure_response", response, *sign], os.path.join(tmp, f"{response}_{path}.csv"))[-1]
    q = {k: v["von_mises"] for k, v in runs.items()}
    pres = {k: v["pressure"] for k, v in runs.items()}
    print("failed point after 1 % strain: response -> (von Mises, pressure) in uniaxial tension-strain and hydrostatic compression:")
    for response in ("none", "zero_stress", "no_shear", "no_tension"):
        print(f"  {response:12s} tension ({q[(response, 'uniaxial_strain')] / 1e6:9.3f}, {pres[(response, 'uniaxial_strain')] / 1e6:9.3f}) MPa, "
              f"compression ({q[(response, 'hydrostatic')] / 1e6:9.3f}, {pres[(response, 'hydrostatic')] / 1e6:9.3f}) MPa, failed flag {int(runs[(response, 'uniaxial_strain')]['failed'])}")
    scale = abs(pres[("none", "uniaxial_strain")])
    check("zero_stress carries nothing (|q| + |p|, tension)", (q[("zero_stress", "uniaxial_strain")] + abs(pres[("zero_stress", "uniaxial_strain")])) / scale, 1e-12, failures)
    check("no_shear has no deviator (tension)", q[("no_shear", "uniaxial_strain")] / scale, 1e-12, failures)
    check("no_shear keeps a pressure (tension): |p| > 0", 1.0 if pres[("no_shear", "uniaxial_strain")] == 0 else 0.0, 0, failures)
    check("no_tension carries nothing in tension", (q[("no_tension", "uniaxial_strain")] + abs(pres[("no_tension", "uniaxial_strain")])) / scale, 1e-12, failures)
    check("no_tension keeps compression: no deviator", q[("no_tension", "hydrostatic")] / scale, 1e-12, failures)
    ok = pres[("no_tension", "hydrostatic")] > 0 and abs(pres[("no_tension", "hydrostatic")] - pres[("none", "hydrostatic")]) / pres[("none", "hydrostatic")] < 1e-12
    print(f"  no_tension keeps the compressive pressure of the intact point: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("no_tension pressure")
    # the wave speed that sets the time step: intact sqrt((K + 4 mu/3)/rho); failed without shear
    # sqrt(K/rho); with no_tension or zero_stress, where nothing is carried below the reference
    # density, at rho no lower than it (a failed point drawn out to J = 15 reported 14.6 km/s in the
    # exploding cylinder and set its step)
    o = options(METAL)
    K, mu, rho0 = float(o["-metal_bulk_modulus"]), float(o["-metal_shear_modulus"]), float(o["-metal_density"])
    expected = {("none", "uniaxial_strain"): lambda r: math.sqrt((K + 4 * mu / 3) / r["density"]),
                ("no_shear", "uniaxial_strain"): lambda r: math.sqrt(K / r["density"]),
                ("no_tension", "uniaxial_strain"): lambda r: math.sqrt(K / max(r["density"], rho0)),
                ("zero_stress", "uniaxial_strain"): lambda r: math.sqrt(K / max(r["density"], rho0)),
                ("no_tension", "hydrostatic"): lambda r: math.sqrt(K / max(r["density"], rho0))}
    for key, value in expected.items():
        r = runs[key]
        check(f"wave speed {key[0]} ({key[1]}, density {r['density']:.6g} kg/m^3): {r['wave_speed']:.6g} m/s against {value(r):.6g}", abs(r["wave_speed"] - value(r)) / value(r), 1e-9, failures)
    ok = runs[("no_tension", "uniaxial_strain")]["density"] < rho0 < runs[("no_tension", "hydrostatic")]["density"]
    print(f"  the tension path draws the point below its reference density, the hydrostatic one above: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("paths")
    ok = q[("none", "uniaxial_strain")] > 0 and all(int(v["failed"]) for v in runs.values())
    print(f"  every point failed and the intact response keeps its deviator: {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("flags")
    finish("failure_response", failures)


def failed_temperature(args):
    """A point of the paper's 4340 set (Mie-Gruneisen, Gamma 1.69) that fails in hydrostatic expansion:
    with zero_stress it carries nothing and does no work, so its temperature stays as it was when it
    failed; without a failure response the isentropic term -Gamma T tr(D) dt keeps cooling it (which
    is what took eroded particles of the cylinder from 600 K to 9 K before)."""
    failures = []
    base = ["-options_file", os.path.join(ROOT, "options/materials/steel_4340_paper.opts"), "-point_path", "velocity_gradient",
            "-point_velocity_gradient", "1,0,0,0,1,0,0,0,1", "-point_rate", "100", "-point_final_strain", "0.3", "-point_steps", "60"]
    with tempfile.TemporaryDirectory() as tmp:
        rows = {r: point(args.burst, base + ["-steel_failure_response", r], os.path.join(tmp, f"{r}.csv")) for r in ("zero_stress", "none")}
    zs = rows["zero_stress"]
    first = next(i for i, row in enumerate(zs) if int(row["failed"]))
    T_fail, T_end = float(zs[first]["temperature"]), float(zs[-1]["temperature"])
    T_none = float(rows["none"][-1]["temperature"])
    print(f"  failed at step {first} of {len(zs) - 1} at {T_fail:.6f} K; zero_stress ends at {T_end:.6f} K; without a response the point ends at {T_none:.3f} K")
    check("zero_stress: |T_end - T_at_failure| (K)", abs(T_end - T_fail), 1e-9, failures)
    ok = T_none < T_fail - 10
    print(f"  without a response the expansion cools the point by more than 10 K (the check can fail): {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("cooling without response")
    finish("failed_temperature", failures)


def failed_closing_temperature(args):
    """A no_tension point of the HY-100 scene's set (Mie-Gruneisen, Gamma = Gamma0 rho0/rho) fails in
    hydrostatic expansion, opens to J = 11 and closes again to J = 6 (-point_reverse_strain): opened it
    carries no pressure, so closing does no work and its temperature stays as it was when it failed.
    The isentropic term -Gamma T tr(D) dt applied while it closes (Gamma0 J = 19 at J = 11) takes it
    from 575 K to 9.7e5 K (the ratchet that heated a failed fragment of the exploding HY-100 cylinder
    to 1e8 K); a closing point that carries pressure (J < 1, response none) still heats."""
    failures = []
    base = ["-options_file", os.path.join(ROOT, "options/materials/hy100_paper.opts"), "-point_path", "velocity_gradient",
            "-point_velocity_gradient", "1,0,0,0,1,0,0,0,1", "-point_rate", "1000", "-point_temperature", "600"]
    with tempfile.TemporaryDirectory() as tmp:
        rows = point(args.burst, base + ["-hy100_failure_response", "no_tension", "-point_reverse_strain", "0.8", "-point_final_strain", "1.0",
                                         "-point_steps", "200"], os.path.join(tmp, "open_close.csv"))
        closed = point(args.burst, base + ["-hy100_failure_response", "none", "-point_velocity_gradient", "-1,0,0,0,-1,0,0,0,-1",
                                           "-point_final_strain", "0.01", "-point_steps", "20"], os.path.join(tmp, "compressed.csv"))
    J = np.array([row["F_xx"] * row["F_yy"] for row in rows]) ** 1.5  # F = f I: J = F_xx^3
    first = next(i for i, row in enumerate(rows) if int(row["failed"]))
    top = int(np.argmax(J))
    T_fail, T_top, T_end = float(rows[first]["temperature"]), float(rows[top]["temperature"]), float(rows[-1]["temperature"])
    print(f"  failed at step {first} (J = {J[first]:.3f}) at {T_fail:.3f} K; opened to J = {J[top]:.2f} at {T_top:.3f} K; closed to J = {J[-1]:.2f} at {T_end:.3f} K")
    check("opened to J > 10 and closed to J < 7 (path)", 0.0 if J[top] > 10 and J[-1] < 7 else 1.0, 0, failures)
    check("no_tension, open: |p| (Pa)", max(abs(float(r["pressure"])) for r in rows[first + 1:]), 0, failures)
    check("no_tension: |T_end - T_at_failure| / T_at_failure (closing does no work)", abs(T_end - T_fail) / T_fail, 1e-12, failures)
    T0, T1 = float(closed[0]["temperature"]), float(closed[-1]["temperature"])
    ok = T1 > T0
    print(f"  an intact point compressed 3 % by volume heats isentropically: {T0:.3f} -> {T1:.3f} K {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("isentropic heating under pressure")
    finish("failed_closing_temperature", failures)


# Johnson & Cook (1985) 4340 Rc 30 data (verification.md 5): rate, T0, stress at eps_p 0/0.05/0.10/0.20 (MPa)
JC_DATA = [("tension", 0.002, 298, [808.7, 968.9, 1042.8, 1135.1]), ("torsion", 0.009, 298, [798.2, 933.4, 988.4, 1027.1]),
           ("torsion", 0.1, 298, [774.9, 899.0, 961.8, 1006.1]), ("torsion", 1.1, 298, [865.6, 1003.3, 1067.1, 1114.7]),
           ("tension", 570, 298, [818.6, 1058.9, 1162.3, None]), ("tension", 604, 500, [753.6, 918.2, 985.5, None]),
           ("tension", 650, 735, [677.8, 827.8, 862.3, None])]


def jc_4340(args):
    deck = os.path.join(ROOT, "options/materials/steel_4340_jc.opts")
    errors = []
    print("Johnson-Cook 4340 (Table 1) against Johnson & Cook (1985), uniaxial stress, isothermal below 1 /s, adiabatic above;")
    print("the data's eps_p = 0 value is compared with the model at 0.2 % offset (the first plastic steps are the elastic-plastic transition):")
    with tempfile.TemporaryDirectory() as tmp:
        for kind, rate, T0, data in JC_DATA:
            adiabatic = "true" if rate > 10 else "false"
            d = point(args.burst, ["-options_file", deck, "-steel_eos_type", "hypoelastic", "-steel_flow_stress_min_rate", "1e-4", "-point_path", "uniaxial_stress",
                                   "-point_rate", str(rate), "-point_temperature", str(T0), "-point_final_strain", "0.23", "-point_steps", "460",
                                   "-point_adiabatic", adiabatic], os.path.join(tmp, "jc.csv"))
            model = []
            for eps, value in zip((0.002, 0.05, 0.10, 0.20), data):
                if value is None:
                    continue
                plastic = d["plastic_strain"] > 0
                sigma = np.interp(eps, d["plastic_strain"][plastic], d["flow_stress"][plastic]) / 1e6
                model.append(sigma)
                errors.append((sigma - value) / value)
            print(f"  {kind:8s} {rate:8g} /s {T0:4d} K: data {[v for v in data if v]} MPa, model {[round(m, 1) for m in model]} MPa")
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    failures = []
    check("RMS relative error against the data", rms, 0.15, failures)
    finish("jc_4340 (validation report)", failures)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("simple_shear")
    s.add_argument("--steps", type=int, default=4000, help="steps of the finer run (the coarser has half)")
    sub.add_parser("linear_hardening")
    sub.add_parser("heating")
    sub.add_parser("jc_4340")
    sub.add_parser("rotation")
    sub.add_parser("failure_response")
    sub.add_parser("failed_temperature")
    sub.add_parser("failed_closing_temperature")
    args = p.parse_args()
    {"simple_shear": simple_shear, "linear_hardening": linear_hardening, "heating": heating, "jc_4340": jc_4340, "rotation": rotation,
     "failure_response": failure_response, "failed_temperature": failed_temperature,
     "failed_closing_temperature": failed_closing_temperature}[args.cmd](args)


if __name__ == "__main__":
    main()
