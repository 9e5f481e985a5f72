#!/usr/bin/python3
"""Two open notes of the Taylor section (README "Taylor impact"), measured.

  scripts/study_taylor_contact.py --burst build/burst [--out doc/figures] [--cpd 16] [--study anvil|floor|all]

--study anvil: why the B-spline foot was narrow. Copper 190 m/s (Johnson-Cook, axisymmetric, MUSL) with
  cpGIMP and B-spline, each on the scene's rigid anvil (its own velocity field, frictionless contact,
  seeded one particle per cell) and on a symmetry wall at the anvil's face instead (the grid starts at
  the anvil top, -bc_ymin symmetry: the same frictionless impact without a contact algorithm), and
  B-spline on the anvil seeded 2 per cell as the scene did before c9ecfa8 (its top particles a quarter
  cell below the face, so that their B-spline support covers the node row one cell above the face,
  inside the rod). Writes taylor_anvil_wall.csv.
--study floor: is the MTS rate floor (-copper_flow_stress_min_rate 1, which the validation cases of
  tests/verify_taylor.py set) still needed? Annealed copper (MTS) at 130, 146 and 190 m/s with the
  model's default floor 1e-3 /s and with 1 /s. Writes taylor_mts_floor_cpdN.csv.
Each row: Lf/L0 and Df/D0 (centres and surface, as summary.json "taylor" gives them), their errors
against the experiment (verification.md 4), the steps, and whether the run reached the 1 % kinetic
energy stop or the 4 L0/U cap, or stopped.
"""
import argparse
import csv
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "options/scenes/taylor.opts")
L0, D0 = 25.4e-3, 7.62e-3  # the scene's defaults (the copper tests)
# experiment (verification.md 4): U -> (Lf mm, Df mm)
EXPERIMENT = {130: (19.56, 9.91), 146: (18.69, 10.67), 190: (16.21, 13.56)}


def wall_options(cpd):
    """The scene's grid (src/scenes/taylor.cxx) cut at the anvil's face, with a symmetry wall there."""
    h = D0 / cpd
    nl = max(1, round(L0 / h))
    hz = L0 / nl
    nr = int(-(-(2.5 * 0.5 * D0 / h - 1e-9) // 1))
    return ["-geometries", "rod", "-materials", "copper", "-bc_ymin", "symmetry", "-grid_lower", f"0,{2 * hz!r}", "-grid_cells", f"{nr},{nl + 2}",
            "-options_allow_unused"]  # the scene's anvil options are then read by nothing


def taylor(burst, velocity, material, cpd, extra):
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", DECK, "-taylor_velocity", str(velocity), "-taylor_material", material, "-taylor_cells_per_diameter", str(cpd),
               "-output_dir", out, "-progress", "false", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        text = proc.stdout + proc.stderr
        if proc.returncode:
            return None, next((line for line in text.splitlines() if "ERROR: Step" in line or "not converge" in line or "return" in line.lower()), "stopped")
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        end = "1 % kinetic stop" if s["taylor"]["stopped_on_kinetic_energy"] else "time cap 4 L0/U"
        return s, end


def row(case, velocity, s, end):
    lf_exp, df_exp = EXPERIMENT[velocity]
    if s is None:
        return dict(case=case, velocity=velocity, end=end)
    t = s["taylor"]
    r = dict(case=case, velocity=velocity)
    for k in ("Lf_centres", "Lf_surface"):
        r[k + "_mm"] = f"{t[k] * 1e3:.4f}"
        r[k + "_error_pct"] = f"{100 * (t[k] * 1e3 / lf_exp - 1):.2f}"
    for k in ("Df_centres", "Df_surface"):
        r[k + "_mm"] = f"{t[k] * 1e3:.4f}"
        r[k + "_error_pct"] = f"{100 * (t[k] * 1e3 / df_exp - 1):.2f}"
    r.update(max_plastic_strain=f"{t['max_plastic_strain']:.3f}", steps=s["steps"], end=end)
    return r


def write(path, rows):
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


def report(r):
    if "Lf_centres_error_pct" in r:
        print(f"{r['case']}: Lf {r['Lf_centres_error_pct']}/{r['Lf_surface_error_pct']} %, Df {r['Df_centres_error_pct']}/{r['Df_surface_error_pct']} % "
              f"(centres/surface), {r['steps']} steps, {r['end']}", flush=True)
    else:
        print(f"{r['case']}: {r['end']}", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--out", default=os.path.join(ROOT, "doc/figures"))
    p.add_argument("--cpd", type=int, default=16)
    p.add_argument("--study", default="all", choices=["anvil", "floor", "all"])
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.study in ("anvil", "all"):
        rows = []
        for shape in ("cpgimp", "bspline2"):
            supports = [("rigid anvil", []), ("symmetry wall", wall_options(a.cpd))]
            if shape == "bspline2":  # the anvil seeded like the rod (the scene's seeding before c9ecfa8): rigid mass inside the rod
                supports.append(("rigid anvil 2 per cell", ["-anvil_particles_per_cell", "2"]))
            for support, extra in supports:
                s, end = taylor(a.burst, 190, "copper_ofhc_jc", a.cpd, ["-mpm_shape_type", shape, *extra])
                rows.append(row(f"cu190 JC {shape} {support} cpd {a.cpd}", 190, s, end))
                report(rows[-1])
        write(os.path.join(a.out, "taylor_anvil_wall.csv"), rows)
    if a.study in ("floor", "all"):
        rows = []
        for velocity in (130, 146, 190):
            for floor in ("1e-3", "1"):
                s, end = taylor(a.burst, velocity, "copper_annealed_mts", a.cpd, ["-copper_flow_stress_min_rate", floor])
                rows.append(row(f"cu{velocity} MTS floor {floor} /s cpd {a.cpd}", velocity, s, end))
                report(rows[-1])
        write(os.path.join(a.out, f"taylor_mts_floor_cpd{a.cpd}.csv"), rows)


if __name__ == "__main__":
    main()
