#!/usr/bin/python3
"""Speed against accuracy: error against cost for each method, with the Pareto front marked.

  scripts/study_speed_accuracy.py --burst build/burst [--out doc/figures] [--quick]

Methods are interpolator x transfer (FLIP, APIC, XPIC(2)) at USL/MUSL; each is run at several
resolutions on
  mms     the axis-aligned manufactured solution, 2-D (tests/decks/mms_axis_aligned.opts): RMS
          displacement error against the exact solution after one period, 8/16/32 cells;
  axisym  the axisymmetric manufactured solution (tests/decks/mms_axisymmetric.opts), the same;
  taylor  the OFHC copper Taylor test at 190 m/s, axisymmetric (options/scenes/taylor.opts): the larger
          of |Lf| and |Df| errors against the experiment (centres), 8/16/32 cells per diameter;
          and its numerical error against the method's own finest run;
  cylinder the prescribed-pressure 4340 cylinder (options/scenes/cylinder2d_4340.opts, quarter, MUSL,
          to 120 us): |energy balance error| (the energy error; the fragment count, which has no
          converged value without a failure length, and the Grady band go into the CSV beside it),
          40/80/160 cells (--cylinder-levels).
Cost: wall time of the stepping (s) and particle-steps; memory as bytes per particle x particles.
Writes OUT/speed_accuracy.csv and OUT/speed_accuracy_<problem>.png (log-log, one line per method,
the Pareto front as black rings: no other run is both cheaper and more accurate). --quick runs two
methods on two resolutions of the mms problem only (the suite's test study_speed_accuracy_quick).
Exits non-zero when a run fails (the chart would miss its point), when --quick's errors do not fall
at second order (QUICK_MIN_ORDER), or when the CSV or a chart is not written.
"""
import argparse
import csv
import json
import os
import math
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TAYLOR = (25.4e-3, 7.62e-3, 16.21e-3, 13.56e-3)  # L0, D0, Lf, Df (verification.md 4, copper 190 m/s)
TRANSFERS = {"flip": [], "apic": ["-mpm_transfer", "apic"], "xpic2": ["-mpm_transfer", "xpic", "-mpm_xpic_order", "2"]}
# --quick: cpGIMP and B-spline on the manufactured solution converge at second order in space (Wallstedt &
# Guilkey 2008); the 8 -> 16 order must be at least 2 less 0.3, the margin tests/verify.py convergence
# allows for the time error and the coarse pair (measured 8 -> 16 at dt 2e-5: cpGIMP FLIP 2.17, B-spline
# APIC 2.33). A first-order method (linear weights) or a broken transfer fails it.
QUICK_MIN_ORDER = 2.0 - 0.3


def run(burst, deck, extra):
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", os.path.join(ROOT, deck), "-output_dir", out, "-progress", "false", "-output_interval", "0", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            return None
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)


def pareto(points):
    """Indices of the points that no other point beats in both cost and error."""
    return [i for i, (c, e) in enumerate(points) if not any(c2 <= c and e2 <= e and (c2, e2) != (c, e) for c2, e2 in points)]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--out", default=os.path.join(ROOT, "doc/figures"))
    p.add_argument("--problems", default="mms,axisym,taylor")
    p.add_argument("--taylor-levels", default="8,16", help="cells per diameter of the Taylor runs")
    p.add_argument("--cylinder-levels", default="40,80,160", help="cells across the quarter of the cylinder runs")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--cost", default="particle_steps", choices=["particle_steps", "wall_s"],
                   help="x axis: particle-steps (deterministic) or the stepping wall time (meaningful on an unloaded machine)")
    p.add_argument("--replot", action="store_true", help="redraw the charts from OUT/speed_accuracy.csv without running")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    shapes = ["linear", "ugimp", "cpgimp", "bspline2"]
    problems = ["mms"] if a.quick else a.problems.split(",")
    rows, failures = [], []
    if a.replot:
        with open(os.path.join(a.out, "speed_accuracy.csv")) as f:
            rows = [{k: (v if k in ("problem", "shape", "transfer", "scheme") else float(v or "nan")) for k, v in r.items()} for r in csv.DictReader(f)]
        problems = sorted({r["problem"] for r in rows}, key=["mms", "axisym", "taylor", "cylinder"].index)
    for prob in ([] if a.replot else problems):
        if a.quick:
            methods = [("cpgimp", "flip", "usl"), ("bspline2", "apic", "usl")]
            levels = [8, 16]
        elif prob == "taylor":
            methods = [(s, "flip", "musl") for s in shapes] + [("cpgimp", "apic", "musl"), ("cpgimp", "xpic2", "musl")]
            levels = [int(v) for v in a.taylor_levels.split(",")]
        elif prob == "cylinder":
            methods = [(s, "flip", "musl") for s in shapes] + [("cpgimp", "apic", "musl")]
            levels = [int(v) for v in a.cylinder_levels.split(",")]
        else:
            methods = [(s, t, "usl") for s in shapes for t in TRANSFERS]
            levels = [8, 16, 32]
        for shape, transfer, scheme in methods:
            finest = None
            for n in reversed(levels):
                if prob in ("mms", "axisym"):
                    deck = "tests/decks/mms_axis_aligned.opts" if prob == "mms" else "tests/decks/mms_axisymmetric.opts"
                    extra = ["-grid_cells", f"{n},{n}", "-mpm_dt", "2e-5"]
                elif prob == "cylinder":
                    deck = "options/scenes/cylinder2d_4340.opts"
                    extra = ["-grid_cells", f"{n},{n}", "-wall_seeding", "lattice", "-grid_upper", "0.12,0.12", "-final_time", "1.2e-4"]  # the form its figures were measured on
                else:
                    deck = "options/scenes/taylor.opts"
                    extra = ["-taylor_cells_per_diameter", str(n), "-mpm_cfl", "0.3" if transfer == "apic" and shape == "linear" else "0.4"]
                s = run(a.burst, deck, ["-mpm_shape_type", shape, "-mpm_scheme", scheme, *TRANSFERS[transfer], *extra])
                if s is None:
                    print(f"{prob} {shape} {transfer} {scheme} n={n}: failed (unstable or stopped)", flush=True)
                    failures.append(f"{prob} {shape} {transfer} {scheme} n={n} did not finish")
                    continue
                if prob == "taylor":
                    t = s["taylor"]
                    el = (t["Lf_centres"] - TAYLOR[2]) / TAYLOR[2]
                    ed = (t["Df_centres"] - TAYLOR[3]) / TAYLOR[3]
                    error = max(abs(el), abs(ed))
                    if finest is None:
                        finest = (t["Lf_centres"], t["Df_centres"])
                    numerical = max(abs(t["Lf_centres"] - finest[0]) / finest[0], abs(t["Df_centres"] - finest[1]) / finest[1])
                elif prob == "cylinder":
                    error = abs(s["energy_balance_error"])
                    if finest is None:
                        finest = s["fragment_count"]
                    numerical = abs(s["fragment_count"] - finest)  # fragments away from the method's finest run
                else:
                    error, numerical = s["displacement_error_rms"], s["displacement_error_rms"]
                row = dict(problem=prob, shape=shape, transfer=transfer, scheme=scheme, resolution=n, error=error, numerical_error=numerical,
                           wall_s=s["wall_time_s"], particle_steps=s["steps"] * s["particles"], memory_bytes=s["bytes_per_particle"] * s["particles"],
                           fragments=s.get("fragment_count", "nan"), grady_shear=s["grady_shear"]["sector"] if "grady_shear" in s else "nan",
                           grady_tension=s["grady_tension"]["sector"] if "grady_tension" in s else "nan")
                rows.append(row)
                print(f"{prob} {shape} {transfer} {scheme} n={n}: error {error:.3e}, numerical {numerical:.3e}, wall {s['wall_time_s']:.2f} s, {row['particle_steps']:.3g} particle-steps", flush=True)
    if a.quick and not a.replot:
        for shape, transfer, scheme in methods:
            err = {int(r["resolution"]): r["error"] for r in rows if (r["shape"], r["transfer"], r["scheme"]) == (shape, transfer, scheme)}
            if len(err) < 2:
                continue  # its failed run is already a failure
            (n0, e0), (n1, e1) = sorted(err.items())[:2]
            order = math.log(e0 / e1) / math.log(n1 / n0) if e0 > 0 and e1 > 0 else float("nan")
            ok = order >= QUICK_MIN_ORDER
            print(f"  {shape} {transfer} {scheme}: observed order {n0} -> {n1} cells {order:.2f} >= {QUICK_MIN_ORDER:g} {'OK' if ok else 'FAIL'}")
            if not ok:
                failures.append(f"{shape} {transfer} order {order:.2f}")
    path = os.path.join(a.out, "speed_accuracy.csv")
    if not a.replot:
        if os.path.exists(path) and not a.quick:  # keep the rows of the problems not rerun
            with open(path) as f:
                kept = [r for r in csv.DictReader(f) if r["problem"] not in problems]  # as written (strings)
            rows = kept + rows
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(dict.fromkeys(k for r in rows for k in r)), restval="nan")
            w.writeheader()
            w.writerows(rows)
        print(f"wrote {path}")
        rows = [{k: (v if k in ("problem", "shape", "transfer", "scheme") or not isinstance(v, str) else float(v or "nan")) for k, v in r.items()} for r in rows]
    for prob in problems:
        sub = [r for r in rows if r["problem"] == prob]
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for key in sorted({(r["shape"], r["transfer"]) for r in sub}):
            pts = sorted((r[a.cost], r["error"]) for r in sub if (r["shape"], r["transfer"]) == key)
            ax.loglog([c for c, _ in pts], [e for _, e in pts], "o-" if key[1] == "flip" else ("s--" if key[1] == "apic" else "^:"), ms=4, label=f"{key[0]} {key[1]}")
        pts = [(r[a.cost], r["error"]) for r in sub]
        front = pareto(pts)
        ax.loglog([pts[i][0] for i in front], [pts[i][1] for i in front], "ko", mfc="none", ms=10, label="Pareto front")
        ax.set_xlabel("particle-steps" if a.cost == "particle_steps" else "wall time of the stepping (s, 1 core)")
        ax.set_ylabel({"mms": "RMS displacement error (m)", "axisym": "RMS displacement error (m)", "taylor": "max(|Lf|, |Df|) error vs experiment",
                       "cylinder": "|energy balance error| / initial energy"}[prob])
        ax.set_title({"mms": "2-D manufactured solution, 8/16/32 cells", "axisym": "axisymmetric manufactured solution, 8/16/32 cells",
                      "taylor": "Taylor, Cu 190 m/s, axisymmetric, 8/16/32 cells per D0",
                      "cylinder": "4340 cylinder, prescribed pressure, " + "/".join(str(int(v)) for v in sorted({r["resolution"] for r in sub})) + " cells"}[prob], fontsize=9)
        if prob == "cylinder":  # the fragment count of each run beside its point
            for r in sub:
                ax.annotate(f"{int(r['fragments'])}", (r[a.cost], r["error"]), textcoords="offset points", xytext=(3, 3), fontsize=6)
        ax.legend(fontsize=6, ncol=2)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        png = os.path.join(a.out, f"speed_accuracy_{prob}.png")
        fig.savefig(png, dpi=110)
        plt.close(fig)
        print(f"wrote {png}")
        if not sub or not os.path.getsize(png):
            failures.append(f"chart {png} empty")
    if failures:
        print(f"study_speed_accuracy: FAIL ({'; '.join(failures)})")
        sys.exit(1)
    print("study_speed_accuracy: OK")


if __name__ == "__main__":
    main()
