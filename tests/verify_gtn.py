#!/usr/bin/python3
"""GTN porosity growth and TEPLA-F failure through the point driver (burst -mode point), against an
independent integration of the rate equations. Prints the measured figures and exits non-zero on
failure.

Material (all options on the command line): elastic_plastic, hypoelastic EOS (K = 170 GPa), mu = 80
GPa, perfectly plastic matrix sigma_y = 500 MPa (linear_hardening, H = 0), GTN yield with the Table 1
constants (q1 1.5, q2 1, q3 2.25, f_c 0.05, k 4), growth (eq. 16) on, nucleation off, f_0 = 0.01,
isothermal. Path: pure dilatation L = r I (tr D = 3 r), r = 1e3 /s, to r t = 0.05.

Rate problem (exact for the continuum model):
  elastic  sigma_m = 3 K r t until the hydrostatic yield point S(f_0);
  plastic  sigma_m = S(f), S(f) = 2 sigma_y/(3 q2) acosh((1 + q3 f*^2)/(2 q1 f*)),
           d sigma_m/dt = K (tr D - tr D_p), df/dt = (1 - f) tr D_p
           => df/dt = (1 - f) tr D / (1 + (1 - f) S'(f)/K),
           d eps_M/dt = sigma_m tr D_p / ((1 - f) sigma_y).
Integrated here with RK4 (200 sub-steps per driver step).

  growth   f, eps_M and sigma_m at 400 and 800 steps: error bounds and observed order (~1).
  tepla    -failure_criteria tepla,porosity, f_c(TEPLA) 0.15, Johnson-Cook damage with eps_f = D1 = 0.3
           (D2 = D4 = D5 = 0): the failed flag flips at the first step where (f/0.15)^2 + (eps/0.3)^2
           >= 1 in the driver's own CSV, and that strain agrees with the rate problem's.

ctest (tests/CMakeLists.txt):
  add_test(NAME verify_gtn_growth COMMAND ${BURST_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/verify_gtn.py --burst $<TARGET_FILE:burst> growth)
  add_test(NAME verify_gtn_tepla COMMAND ${BURST_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/verify_gtn.py --burst $<TARGET_FILE:burst> tepla)
  set_tests_properties(verify_gtn_growth verify_gtn_tepla PROPERTIES LABELS verification)
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

Q1, Q2, Q3, FC, KACC = 1.5, 1.0, 2.25, 0.05, 4.0
K, SY, RATE, F0 = 170e9, 500e6, 1e3, 0.01
FINAL = 0.05

MATERIAL = [
    "-materials", "g", "-g_model", "elastic_plastic", "-g_density", "7830", "-g_shear_modulus", "80e9", "-g_bulk_modulus", "170e9",
    "-g_room_temperature", "298", "-g_adiabatic", "false", "-g_eos_type", "hypoelastic", "-g_melt_type", "constant", "-g_melt_Tm", "1800",
    "-g_shear_modulus_type", "constant", "-g_specific_heat_type", "constant", "-g_specific_heat_Cp", "477",
    "-g_flow_stress_type", "linear_hardening", "-g_flow_stress_yield_stress", "500e6", "-g_flow_stress_hardening_modulus", "0",
    "-g_yield_type", "gtn", "-g_porosity_growth", "true", "-g_porosity_nucleation", "false", "-g_porosity_initial_mean", "0.01",
    "-g_porosity_initial_deviation", "0", "-g_return_tolerance", "1e-12",
]


def fstar(f):
    return (f, 1.0) if f <= FC else (FC + KACC * (f - FC), KACC)


def S(f):
    fs, _ = fstar(f)
    return 2 * SY / (3 * Q2) * math.acosh((1 + Q3 * fs * fs) / (2 * Q1 * fs))


def dS(f):
    fs, d = fstar(f)
    z = (1 + Q3 * fs * fs) / (2 * Q1 * fs)
    dz = (Q3 * fs * fs - 1) / (2 * Q1 * fs * fs)
    return 2 * SY / (3 * Q2) * dz / math.sqrt(z * z - 1) * d


def rhs(y):
    f = y[0]
    fd = (1 - f) * 3 * RATE / (1 + (1 - f) * dS(f) / K)
    return np.array([fd, S(f) * fd / ((1 - f) ** 2 * SY)])


def ode(times, substeps=200):
    """(f, eps_M, sigma_m) of the rate problem at the given ascending times."""
    ty = S(F0) / (3 * K * RATE)
    y, t, out = np.array([F0, 0.0]), ty, []
    for T in times:
        if T <= ty:
            out.append((F0, 0.0, 3 * K * RATE * T))
            continue
        h = (T - t) / substeps
        for _ in range(substeps):
            k1 = rhs(y)
            k2 = rhs(y + 0.5 * h * k1)
            k3 = rhs(y + 0.5 * h * k2)
            k4 = rhs(y + h * k3)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t = T
        out.append((y[0], y[1], S(y[0])))
    return np.array(out)


def drive(burst, steps, extra, tmp):
    out = os.path.join(tmp, f"point_{steps}.csv")
    cmd = [burst, "-mode", "point", *MATERIAL, *extra, "-point_path", "hydrostatic", "-point_rate", str(RATE),
           "-point_final_strain", str(FINAL), "-point_steps", str(steps), "-point_output", out]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-4000:] + proc.stderr[-4000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    with open(out) as f:
        rows = list(csv.DictReader(f))[1:]  # drop the initial state
    col = lambda k: np.array([float(r[k]) for r in rows])
    return {"time": col("time"), "strain": col("strain"), "f": col("porosity"), "eps": col("plastic_strain"),
            "sm": -col("pressure"), "failed": np.array([int(r["failed"]) for r in rows])}


def check(name, value, tol, failures, lo=None):
    ok = value <= tol if lo is None else lo <= value <= tol
    rng = f"tol {tol:g}" if lo is None else f"range [{lo:g}, {tol:g}]"
    print(f"  {name}: {value:.3e} ({rng}) {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append(name)


def growth(args):
    failures, errs = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for steps in (400, 800):
            h = drive(args.burst, steps, ["-g_failure_criteria", "none"], tmp)
            ex = ode(h["time"])
            e = (np.max(np.abs(h["f"] - ex[:, 0])), np.max(np.abs(h["eps"] - ex[:, 1])), np.max(np.abs(h["sm"] - ex[:, 2])) / SY)
            errs.append(e)
            print(f"  {steps} steps: final f {h['f'][-1]:.6f} (ODE {ex[-1, 0]:.6f}), eps_M {h['eps'][-1]:.6f} (ODE {ex[-1, 1]:.6f}), "
                  f"sigma_m {h['sm'][-1] / 1e6:.4f} MPa (ODE {ex[-1, 2] / 1e6:.4f} MPa)")
    check("800 steps: max |f - f_ODE|", errs[1][0], 5e-5, failures)
    check("800 steps: max |eps_M - eps_M,ODE|", errs[1][1], 6e-4, failures)
    check("800 steps: max |sigma_m - sigma_m,ODE| / sigma_y", errs[1][2], 1e-3, failures)
    for j, name in enumerate(("f", "eps_M", "sigma_m")):
        check(f"observed order ({name}, 400/800 steps)", math.log2(errs[0][j] / errs[1][j]), 1.3, failures, lo=0.7)
    finish("verify_gtn growth", failures)


def tepla(args):
    failures = []
    fct, epsf, steps = 0.15, 0.3, 800
    extra = ["-g_failure_criteria", "tepla,porosity", "-g_failure_porosity", str(fct), "-g_damage_type", "johnson_cook", "-g_damage_D1", str(epsf),
             "-g_damage_D2", "0", "-g_damage_D3", "-2.12", "-g_damage_D4", "0", "-g_damage_D5", "0"]
    with tempfile.TemporaryDirectory() as tmp:
        h = drive(args.burst, steps, extra, tmp)
    g = (h["f"] / fct) ** 2 + (h["eps"] / epsf) ** 2
    flips = np.nonzero(h["failed"])[0]
    if not len(flips):
        raise SystemExit("verify_gtn tepla: FAIL (never failed)")
    flip, own = flips[0], np.nonzero(g >= 1)[0][0]
    # the rate problem's failure strain, by bisection
    lo, hi = 0.01, FINAL
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        s = ode([mid / RATE], 2000)[0]
        (lo, hi) = (mid, hi) if (s[0] / fct) ** 2 + (s[1] / epsf) ** 2 < 1 else (lo, mid)
    ode_strain = 0.5 * (lo + hi)
    print(f"  flip at step {flip + 1}, strain {h['strain'][flip]:.6f} (f {h['f'][flip]:.5f}, eps_M {h['eps'][flip]:.5f}, bits {h['failed'][flip]}); "
          f"own history crosses at step {own + 1}; rate problem: strain {ode_strain:.6f}")
    check("flip step - first step with (f/fc)^2 + (eps/eps_f)^2 >= 1", abs(flip - own), 0, failures)
    check("failure bits at the flip (2 = tepla alone)", abs(h["failed"][flip] - 2), 0, failures)
    check("|strain at flip - rate problem| / strain", abs(h["strain"][flip] - ode_strain) / ode_strain, 5e-3, failures)
    finish("verify_gtn tepla", failures)


def finish(test, failures):
    if failures:
        print(f"{test}: FAIL ({', '.join(failures)})")
        sys.exit(1)
    print(f"{test}: OK")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True, help="path of the burst executable")
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("growth")
    sub.add_parser("tepla")
    args = p.parse_args()
    {"growth": growth, "tepla": tepla}[args.cmd](args)


if __name__ == "__main__":
    main()
