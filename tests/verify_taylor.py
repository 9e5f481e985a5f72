#!/usr/bin/python3
"""Taylor anvil impact against the Johnson & Cook (1983) tests (verification.md 4), through
options/scenes/taylor.opts. For each test: final length Lf and foot diameter Df from particle centres
and from centres plus the deformed half-size (the two bracket the surface), their errors against the
experiment, and for 4340 at 208 m/s the RMS radius error against the digitised profile.

  validate   run a list of tests (--cases), print the table, write taylor_validation.csv and
             one PNG per run (scripts/plot_taylor.py) to --out, and gate: |Lf error| and |Df error|
             of both measures (centres, surface) within the material's tolerance (TOLERANCE below,
             or --tol-lf / --tol-df; --check df gates Df alone), and for st208 the profile's RMS
             radius error within one cell
  parallel   the same coarse run on 1 and 2 ranks: Lf, Df and the energies agree
  sensitivity  one test under one change at a time (resolution, particles per cell, stop, heating,
             rate term, interpolator, step order, bulk viscosity, friction, EOS): what moves Lf and Df

Cases: cu130 cu146 cu190 (OFHC copper, Johnson-Cook), cu130_mts cu146_mts cu190_mts (annealed copper,
MTS), st208 st282 st343 (4340 steel, Johnson-Cook).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "options/scenes/taylor.opts")
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]

# verification.md 4: U (m/s), L0, D0, Lf, Df (mm)
TESTS = {
    "cu130": ("copper_ofhc_jc", 130, 25.40, 7.62, 19.56, 9.91),
    "cu146": ("copper_ofhc_jc", 146, 25.40, 7.62, 18.69, 10.67),
    "cu190": ("copper_ofhc_jc", 190, 25.40, 7.62, 16.21, 13.56),
    "cu130_mts": ("copper_annealed_mts", 130, 25.40, 7.62, 19.56, 9.91),
    "cu146_mts": ("copper_annealed_mts", 146, 25.40, 7.62, 18.69, 10.67),
    "cu190_mts": ("copper_annealed_mts", 190, 25.40, 7.62, 16.21, 13.56),
    "st208": ("steel_4340_jc", 208, 25.40, 7.62, 22.48, 11.10),
    "st282": ("steel_4340_jc", 282, 12.70, 7.62, 10.71, 10.40),
    "st343": ("steel_4340_jc", 343, 8.10, 7.62, 6.54, 12.00),
}
# The MTS return mapping (models/plasticity) fails its Newton iterations at the default rate floor
# (1e-3 /s) for a copper particle at eps_p 0.63, 263 /s, 348 K (cu130, 16 cells per diameter, t = 50 us);
# the MTS runs therefore floor the rate at 1 /s, far below the rates of the test (1e2-1e5 /s), where it
# changes no flow stress that matters here.
CASE_OPTIONS = {"cu130_mts": ["-copper_flow_stress_min_rate", "1"], "cu146_mts": ["-copper_flow_stress_min_rate", "1"],
                "cu190_mts": ["-copper_flow_stress_min_rate", "1"]}
# The gate of `validate`, per material file: the largest |error| (%) of Lf and of Df, both measures, against
# the experiment (Johnson & Cook 1983, verification.md 4). The slack is the constitutive model's own
# error, which no grid removes (README, Taylor impact), plus the part of Df the grid has not converged:
#  - Johnson-Cook (copper and 4340): the rate term C ln(rate) fitted well below the foot's 1e4-1e5 /s
#    biases the rod long (copper, Lf +5 to +7 %) and changes Df by up to 12 points when C alone is varied
#    (sensitivity study, cu190); Df is not converged at 32 cells per diameter (it grows by 4 points from
#    16 to 32). An independent MPM code with the same JC copper constants (Uintah, GIMP, 0.5 mm) gives
#    Lf +8.5 %, Df -10 to -14 % on cu190. Bound: Lf 10 %, Df 15 %, the band that code reaches. Measured
#    (32 cells per diameter, axisymmetric, 2026-12-03): worst Lf -8.6 % (st343, whose digitised profile
#    is itself 8 % off in volume), worst Df +11.8 % (cu130); 3-D quarter at 16: Lf +6.8 %, Df +8.2 %.
#  - MTS (annealed copper): its rate dependence through thermal activation follows the test; measured
#    at 32 cells per diameter Lf +1.2 to +4.8 %, Df -3.5 to +4.9 %. Bound: Lf 7 %, Df 8 %: the measured
#    worst plus the 3-4 points Df moves between 16 and 32 cells per diameter (cu190_mts -7.1 -> -3.5 %),
#    well inside the JC band, so an MTS run that fell back to JC-like error would fail.
TOLERANCE = {"copper_ofhc_jc": (10.0, 15.0), "steel_4340_jc": (10.0, 15.0), "copper_annealed_mts": (7.0, 8.0)}
# verification.md 4: digitised profile of 4340 at 208 m/s (z, r in mm)
PROFILE_ST208 = ([0, 2.10, 4.02, 6.00, 8.09, 10.11, 12.15, 14.26, 16.30, 18.31, 20.36, 22.50],
                 [5.528, 4.780, 4.300, 4.033, 3.979, 3.881, 3.881, 3.748, 3.783, 3.774, 3.765, 3.810])


def run(burst, case, out, cpd, ppc, dim, ranks, extra):
    material, U, L0, D0, _, _ = TESTS[case]
    cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [
        burst, "-options_file", DECK, "-output_dir", out, "-progress", "false", "-scene", f"taylor_{case}",
        "-taylor_material", material, "-taylor_velocity", str(U), "-taylor_length", f"{L0}e-3", "-taylor_diameter", f"{D0}e-3",
        "-taylor_cells_per_diameter", str(cpd), "-taylor_particles_per_cell", str(ppc), "-dim", str(dim), *CASE_OPTIONS.get(case, []), *extra]
    t0 = time.time()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.time() - t0
    if proc.returncode != 0:
        why = [line for line in (proc.stdout + proc.stderr).splitlines() if "failed" in line or "PETSC ERROR: Step" in line or "not finite" in line]
        sys.stdout.write("\n".join(why[:3]) + "\n" if why else proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    s["wall_total_s"] = wall
    return s


def profile_error(out):
    """RMS over the digitised heights of (model radius - measured radius), mm, model radius from the
    surface profile (largest centre + half-size per bin), interpolated at each height."""
    import numpy as np
    prof = np.genfromtxt(os.path.join(out, "taylor_profile.csv"), delimiter=",", names=True)
    z, r = 1e3 * prof["z_m"], 1e3 * prof["r_surface_m"]
    ze, re = np.array(PROFILE_ST208[0]), np.array(PROFILE_ST208[1])
    keep = ze <= z.max()
    rm = np.interp(ze[keep], z, r)
    return float(np.sqrt(np.mean((rm - re[keep]) ** 2)))


def validate(args):
    cases = args.cases.split(",")
    rows, failures = [], []
    os.makedirs(args.out, exist_ok=True)
    print(f"Taylor validation: {args.dim}-D{' (axisymmetric)' if args.dim == 2 else ' quarter'}, {args.cpd} cells per diameter, {args.ppc} particles per cell, {args.ranks} rank(s) {args.extra}")
    print(f"{'case':10s} {'Lf/L0 exp':>9s} {'Lf/L0 model':>14s} {'Lf error %':>14s} {'Df/D0 exp':>9s} {'Df/D0 model':>14s} {'Df error %':>14s} {'eps_max':>7s} {'T_max':>6s} {'t_end us':>8s} {'wall s':>7s}")
    for case in cases:
        material, U, L0, D0, Lf, Df = TESTS[case]
        out = os.path.join(args.out, case)
        os.makedirs(out, exist_ok=True)
        try:
            s = run(args.burst, case, out, args.cpd, args.ppc, args.dim, args.ranks, args.extra.split())
        except SystemExit as e:
            print(f"{case:10s} burst stopped: {e}")
            failures.append(f"{case} run")
            continue
        t = s["taylor"]
        lf = [1e3 * t["Lf_centres"], 1e3 * t["Lf_surface"]]
        df = [1e3 * t["Df_centres"], 1e3 * t["Df_surface"]]
        elf = [100 * (v - Lf) / Lf for v in lf]
        edf = [100 * (v - Df) / Df for v in df]
        row = dict(case=case, material=material, velocity=U, dim=args.dim, cells_per_diameter=args.cpd, particles_per_cell=args.ppc,
                   Lf_exp_mm=Lf, Lf_centres_mm=lf[0], Lf_surface_mm=lf[1], Lf_err_centres_pct=elf[0], Lf_err_surface_pct=elf[1],
                   Df_exp_mm=Df, Df_centres_mm=df[0], Df_surface_mm=df[1], Df_err_centres_pct=edf[0], Df_err_surface_pct=edf[1],
                   D02_centres_mm=1e3 * t["D02_centres"], max_plastic_strain=t["max_plastic_strain"], max_temperature_K=t["max_temperature"],
                   end_time_us=1e6 * s["final_time"], stopped_on_kinetic=t["stopped_on_kinetic_energy"], steps=s["steps"],
                   particles=s["particles"], particle_steps=s["steps"] * s["particles"], wall_s=s["wall_time_s"], ranks=args.ranks)
        extra = ""
        if case == "st208":
            row["profile_rms_mm"] = profile_error(out)
            extra = f" profile RMS {row['profile_rms_mm']:.3f} mm"
        tol_lf = args.tol_lf if args.tol_lf is not None else TOLERANCE[material][0]
        tol_df = args.tol_df if args.tol_df is not None else TOLERANCE[material][1]
        row["tol_lf_pct"], row["tol_df_pct"] = tol_lf, tol_df
        rows.append(row)
        print(f"{case:10s} {Lf / L0:9.3f} {lf[0] / L0:6.3f}-{lf[1] / L0:6.3f} {elf[0]:+6.1f} {elf[1]:+6.1f} {Df / D0:9.3f} {df[0] / D0:6.3f}-{df[1] / D0:6.3f} "
              f"{edf[0]:+6.1f} {edf[1]:+6.1f} {t['max_plastic_strain']:7.2f} {t['max_temperature']:6.0f} {1e6 * s['final_time']:8.1f} {s['wall_time_s']:7.1f}{extra}")
        if args.plot:
            exp = ";".join(f"{r},{z}" for z, r in zip(*PROFILE_ST208)) if case == "st208" else None
            cmd = [sys.executable, os.path.join(ROOT, "scripts/plot_taylor.py"), out, "--png", os.path.join(args.out, f"taylor_{case}.png")]
            if exp:
                cmd += ["--experiment", exp]
            subprocess.run(cmd, check=True, capture_output=True)
        for name, errs, tol, given in (("Lf", elf, tol_lf, args.tol_lf), ("Df", edf, tol_df, args.tol_df)):
            if name.lower() not in args.check:
                print(f"  {case} {name} not gated (--check {','.join(args.check)})")
                continue
            ok = max(abs(e) for e in errs) <= tol
            print(f"  {case} {name} error {errs[0]:+.1f} % (centres), {errs[1]:+.1f} % (surface) within {tol:g} % "
                  f"({'given' if given is not None else material + ' model band'}): {'OK' if ok else 'FAIL'}")
            if not ok:
                failures.append(f"{case} {name}")
        if case == "st208":
            # the profile: the surface radius of a column of particles is known to one cell (D0/cpd)
            h = D0 / args.cpd
            ok = row["profile_rms_mm"] <= h
            print(f"  {case} profile RMS radius error {row['profile_rms_mm']:.3f} mm within one cell {h:.3f} mm: {'OK' if ok else 'FAIL'}")
            if not ok:
                failures.append(f"{case} profile")
    if not rows:
        print("taylor validation: FAIL (no run finished)")
        sys.exit(1)
    path = os.path.join(args.out, "taylor_validation.csv")
    with open(path, "w", newline="") as f:
        keys = sorted({k for r in rows for k in r}, key=lambda k: list(rows[0]).index(k) if k in rows[0] else 99)
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    if failures:
        print(f"taylor validation: FAIL ({', '.join(failures)})")
        sys.exit(1)
    print("taylor validation: OK")


def parallel(args):
    failures = []
    res = []
    for ranks in (1, 2):
        with tempfile.TemporaryDirectory() as out:
            res.append(run(args.burst, args.case, out, args.cpd, args.ppc, args.dim, ranks, args.extra.split()))
    t1, t2 = res[0]["taylor"], res[1]["taylor"]
    print(f"taylor {args.case} {args.dim}-D on 1 and 2 ranks: Lf {1e3 * t1['Lf_centres']:.6f} / {1e3 * t2['Lf_centres']:.6f} mm, Df {1e3 * t1['Df_centres']:.6f} / {1e3 * t2['Df_centres']:.6f} mm, steps {res[0]['steps']} / {res[1]['steps']}")
    for key in ("Lf_centres", "Lf_surface", "Df_centres", "Df_surface", "max_plastic_strain", "max_temperature"):
        d = abs(t1[key] - t2[key]) / max(abs(t1[key]), 1e-300)
        ok = d <= args.tol
        print(f"  {key} relative difference {d:.2e} (tol {args.tol:g}) {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(key)
    if res[0]["steps"] != res[1]["steps"]:
        failures.append("steps")
    print(f"taylor parallel: {'FAIL (' + ', '.join(failures) + ')' if failures else 'OK'}")
    sys.exit(1 if failures else 0)


SENSITIVITY = [
    ("reference", []),
    ("8 cells per diameter", ["-taylor_cells_per_diameter", "8"]),
    ("32 cells per diameter", ["-taylor_cells_per_diameter", "32"]),
    ("4 particles per cell (per direction)", ["-taylor_particles_per_cell", "4"]),
    ("run to 100 us instead of the 1 % kinetic-energy stop", ["-stop_kinetic_fraction", "0", "-final_time", "100e-6"]),
    ("no plastic heating (Taylor-Quinney 0)", ["-MAT_taylor_quinney", "0"]),
    ("no rate term (JC C = 0)", ["-MAT_flow_stress_C", "0"]),
    ("JC C halved (0.0125)", ["-MAT_flow_stress_C", "0.0125"]),
    ("B-spline interpolator", ["-mpm_shape_type", "bspline2"]),
    ("linear interpolator", ["-mpm_shape_type", "linear"]),
    ("USL instead of MUSL", ["-mpm_scheme", "usl"]),
    ("artificial bulk viscosity 0.2, 2.0", ["-mpm_artificial_viscosity", "0.2,2.0"]),
    ("anvil friction 0.1", ["-mpm_contact_friction", "0.1"]),
    ("hypoelastic pressure (no Mie-Gruneisen)", ["-MAT_eos_type", "hypoelastic"]),
]


def sensitivity(args):
    material = TESTS[args.case][0]
    mat = "copper" if "copper" in material else "steel"
    _, U, L0, D0, Lf, Df = TESTS[args.case]
    print(f"Taylor sensitivity, {args.case} ({material}, {U} m/s), {args.cpd} cells per diameter, {args.ppc} particles per cell, axisymmetric")
    print(f"{'change':48s} {'Lf error %':>14s} {'Df error %':>14s} {'t_end us':>8s}")
    for label, opts in SENSITIVITY:
        opts = [o.replace("-MAT_", f"-{mat}_") for o in opts]
        with tempfile.TemporaryDirectory() as out:
            try:
                s = run(args.burst, args.case, out, args.cpd, args.ppc, 2, 1, opts)
            except SystemExit as e:
                print(f"{label:48s} failed: {e}")
                continue
        t = s["taylor"]
        elf = [100 * (1e3 * t[k] - Lf) / Lf for k in ("Lf_centres", "Lf_surface")]
        edf = [100 * (1e3 * t[k] - Df) / Df for k in ("Df_centres", "Df_surface")]
        print(f"{label:48s} {elf[0]:+6.1f} {elf[1]:+6.1f} {edf[0]:+6.1f} {edf[1]:+6.1f} {1e6 * s['final_time']:8.1f}", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    sub = p.add_subparsers(dest="cmd", required=True)
    v = sub.add_parser("validate")
    v.add_argument("--cases", default="cu130,cu146,cu190,cu130_mts,cu146_mts,cu190_mts,st208,st282,st343")
    v.add_argument("--cpd", type=int, default=32, help="cells per diameter")
    v.add_argument("--ppc", type=int, default=2, help="particles per cell per direction")
    v.add_argument("--dim", type=int, default=2)
    v.add_argument("--ranks", type=int, default=1)
    v.add_argument("--extra", default="")
    v.add_argument("--out", default="taylor_validation")
    v.add_argument("--plot", action="store_true")
    v.add_argument("--check", type=lambda t: t.split(","), default=["lf", "df"], help="the measures to gate, lf,df (default both)")
    v.add_argument("--tol-lf", type=float, default=None, help="gate: |Lf error| (%%) of both measures (default: the material's, TOLERANCE)")
    v.add_argument("--tol-df", type=float, default=None, help="gate: |Df error| (%%) of both measures (default: the material's, TOLERANCE)")
    q = sub.add_parser("parallel")
    q.add_argument("--case", default="cu190")
    q.add_argument("--cpd", type=int, default=8)
    q.add_argument("--ppc", type=int, default=2)
    q.add_argument("--dim", type=int, default=2)
    q.add_argument("--tol", type=float, default=1e-10)
    q.add_argument("--extra", default="")
    e = sub.add_parser("sensitivity")
    e.add_argument("--case", default="cu190")
    e.add_argument("--cpd", type=int, default=16)
    e.add_argument("--ppc", type=int, default=2)
    args = p.parse_args()
    if args.cmd == "validate" and (not args.check or not set(args.check) <= {"lf", "df"}):
        p.error(f"--check {','.join(args.check)}: give lf, df or lf,df (a gate on nothing checks nothing)")
    {"validate": validate, "parallel": parallel, "sensitivity": sensitivity}[args.cmd](args)


if __name__ == "__main__":
    main()
