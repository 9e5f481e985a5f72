#!/usr/bin/python3
"""Runs the same short runs with two burst executables and checks that they give the same answer bit
for bit: the summary (every field but the wall-clock figures), monitor.csv, fragments.csv and the
last particle, grid and gas files (every dataset, exact equality). For a change that must not change
behaviour (a refactor): build the old tree and the new one, then

  python3 scripts/compare_builds.py --old /tmp/old/build/burst --new build/burst [--only NAME,...]
                                   [--allow-new-fields]

The runs cover every scene of options/scenes/ (coarse, a few dozen steps) on 1 and 2 ranks, the
material-point driver and the decks whose models or phases the scenes do not reach. Exits 1 on the
first run that differs (naming the file and field), 0 when all agree.
"""
import argparse
import csv
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from verify_checkpoint import h5_arrays  # noqa: E402  (every dataset of an HDF5 file)
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe"]
WALL_CLOCK = ("wall_time", "per_second", "seconds", "stress_shared")  # summary fields that time the machine, not the physics

SHORT2D = "-grid_cells 32,32 -max_steps 40 -output_interval 20"
RUNS = [  # name, ranks, options
    ("exploding_cylinder2d", 1, "-options_file options/scenes/exploding_cylinder2d.opts -grid_cells 40,40 -max_steps 60 -output_interval 30"),
    ("exploding_cylinder2d_2ranks", 2, "-options_file options/scenes/exploding_cylinder2d.opts -grid_cells 40,40 -max_steps 60 -output_interval 30"),
    ("exploding_cylinder2d_elastic", 2, "-options_file options/scenes/exploding_cylinder2d_elastic.opts -grid_cells 40,40 -max_steps 60 -output_interval 30"),
    ("exploding_cylinder2d_hy100", 1, "-options_file options/scenes/exploding_cylinder2d_hy100.opts -grid_cells 40,40 -max_steps 40 -output_interval 20"),
    ("exploding_cylinder3d", 2, "-options_file options/scenes/exploding_cylinder3d.opts -grid_cells 16,16,8 -max_steps 10 -output_interval 5"),
    ("cylinder2d_4340", 2, "-options_file options/scenes/cylinder2d_4340.opts " + SHORT2D),
    ("cylinder2d_hy100", 1, "-options_file options/scenes/cylinder2d_hy100.opts " + SHORT2D),
    ("ring2d", 2, "-options_file options/scenes/ring2d.opts -grid_cells 40,40 -output_interval 300"),
    ("colliding_disks", 1, "-options_file options/scenes/colliding_disks.opts " + SHORT2D),
    ("spheres3d", 2, "-options_file options/scenes/spheres3d.opts -grid_cells 12,12,12 -max_steps 20 -output_interval 10"),
    ("taylor", 2, "-options_file options/scenes/taylor.opts -max_steps 40 -output_interval 20"),
    ("blast2d", 2, "-options_file options/scenes/blast2d.opts -grid_cells 40,40 -max_steps 40 -output_interval 20"),
    ("sod", 1, "-options_file options/scenes/sod.opts -max_steps 40 -output_interval 20"),
    ("shock_tube_air", 1, "-options_file options/scenes/shock_tube_air.opts -max_steps 40 -output_interval 20"),
    ("softening_bar", 1, "-options_file tests/decks/softening_bar.opts -output_interval 200"),
    ("softening_bar_nonlocal", 2, "-options_file tests/decks/softening_bar.opts -output_interval 200 -bar_regularization nonlocal -bar_regularization_length 5e-4"),
    ("softening_bar_crack_band", 1, "-options_file tests/decks/softening_bar.opts -output_interval 200 -bar_regularization crack_band -bar_fracture_energy 5e3 -bar_failure_porosity 0.02 -final_time 4e-6"),
    ("tension_ring", 2, "-options_file tests/decks/tension_ring.opts -max_steps 40 -output_interval 20"),
    ("burning_block", 1, "-options_file tests/decks/burning_block.opts -max_steps 40 -output_interval 20"),
    ("plate_impact", 1, "-options_file tests/decks/plate_impact.opts -max_steps 40 -output_interval 20"),
    ("point_4340_paper", 1, "-mode point -options_file options/materials/steel_4340_paper.opts -point_path uniaxial_stress -point_rate 1e4 -point_final_strain 0.4 -point_steps 400 -point_output {out}/point.csv"),
    ("point_viscoscram", 1, "-mode point -options_file options/materials/pbx9501_viscoscram.opts -point_path velocity_gradient -point_velocity_gradient -1,0,0,0,0,0,0,0,0 -point_rate 1e4 -point_final_strain 0.05 -point_steps 200 -point_output {out}/point.csv"),
]


def run(exe, ranks, options, out):
    os.makedirs(out, exist_ok=True)
    given = options.format(out=out).split() + ([] if "{out}" in options else ["-output_dir", out])
    cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [exe, *given]
    proc = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return proc.returncode, proc.stdout


def summary_fields(d, prefix=""):
    """The summary flattened to (key, value), without the wall-clock figures."""
    out = {}
    for k, v in d.items():
        key = prefix + k
        if any(w in k for w in WALL_CLOCK):
            continue
        if isinstance(v, dict):
            out.update(summary_fields(v, key + "."))
        else:
            out[key] = v
    return out


def compare(a, b, allow_new=False):
    """The first difference between two output folders, or None (with allow_new, summary fields and
    monitor columns that only the new build writes are no difference)."""
    sa, sb = os.path.join(a, "summary.json"), os.path.join(b, "summary.json")
    if os.path.exists(sa) != os.path.exists(sb):
        return "summary.json: written by one build only"
    if os.path.exists(sa):
        fa, fb = summary_fields(json.load(open(sa))), summary_fields(json.load(open(sb)))
        for k in sorted(set(fa) | set(fb)):
            if allow_new and k not in fa:
                continue
            if fa.get(k) != fb.get(k):
                return f"summary.json {k}: {fa.get(k)!r} against {fb.get(k)!r}"
    for name in ("monitor.csv", "fragments.csv", "point.csv"):
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if os.path.exists(pa) or os.path.exists(pb):
            if not (os.path.exists(pa) and os.path.exists(pb)):
                return f"{name}: written by one build only"
            ra, rb = list(csv.reader(open(pa))), list(csv.reader(open(pb)))
            if allow_new and ra and rb and ra[0] != rb[0] and set(ra[0]) <= set(rb[0]):
                keep = [rb[0].index(c) for c in ra[0]]  # the columns both write
                rb = [[row[k] for k in keep] for row in rb]
            if ra != rb:
                return f"{name} differs"
    for stem in ("particles", "grid", "gas"):
        la, lb = sorted(glob.glob(os.path.join(a, stem + "_*.h5"))), sorted(glob.glob(os.path.join(b, stem + "_*.h5")))
        if [os.path.basename(p) for p in la] != [os.path.basename(p) for p in lb]:
            return f"{stem}_*.h5: different files"
        if not la:
            continue
        da, db = h5_arrays(la[-1]), h5_arrays(lb[-1])
        if sorted(da) != sorted(db):
            return f"{os.path.basename(la[-1])}: datasets {sorted(set(da) ^ set(db))} in one build only"
        for k in da:
            x, y = np.asarray(da[k]), np.asarray(db[k])
            if x.shape != y.shape or x.dtype != y.dtype or not np.array_equal(x, y, equal_nan=True):
                return f"{os.path.basename(la[-1])} {k}: differs"
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True, help="the reference burst executable")
    ap.add_argument("--new", default=os.path.join(ROOT, "build", "burst"), help="the executable under test")
    ap.add_argument("--only", default="", help="comma-separated run names (default: all)")
    ap.add_argument("--keep", action="store_true", help="keep the output folders")
    ap.add_argument("--allow-new-fields", action="store_true", help="summary fields that only the new build writes are no difference")
    args = ap.parse_args()
    only = set(filter(None, args.only.split(",")))
    work = tempfile.mkdtemp(prefix="compare_builds_")
    failures = 0
    for name, ranks, options in RUNS:
        if only and name not in only:
            continue
        results = []
        for tag, exe in (("old", args.old), ("new", args.new)):
            out = os.path.join(work, f"{name}_{tag}")
            results.append(run(os.path.abspath(exe), ranks, options, out))
        (rc_old, log_old), (rc_new, log_new) = results
        if rc_old != 0 or rc_new != 0:
            diff = f"exit codes {rc_old} / {rc_new}" if rc_old != rc_new else (None if rc_old == rc_new and log_old.splitlines()[-1:] == log_new.splitlines()[-1:] else "both failed differently")
            if rc_old != 0 and rc_new == rc_old:
                print(f"{name:34s} both runs stop ({rc_old}): {log_old.strip().splitlines()[-1] if log_old.strip() else ''}")
            if diff:
                print(f"{name:34s} DIFFERS: {diff}\n{log_new[-2000:]}")
                failures += 1
            continue
        diff = compare(os.path.join(work, f"{name}_old"), os.path.join(work, f"{name}_new"), args.allow_new_fields)
        print(f"{name:34s} {'DIFFERS: ' + diff if diff else 'bit for bit'} ({ranks} rank{'s' if ranks > 1 else ''})")
        failures += diff is not None
        sys.stdout.flush()
    if not args.keep:
        shutil.rmtree(work)
    else:
        print("outputs in", work)
    print(f"{'all runs agree bit for bit' if not failures else str(failures) + ' run(s) differ'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
