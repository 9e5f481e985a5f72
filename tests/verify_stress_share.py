#!/usr/bin/env python3
"""The stress update shared between ranks (-mpm_stress_share, src/mpm/stress_share.cxx) gives the run
without sharing bit for bit.

Runs a deck on N ranks twice, with -mpm_stress_share 1 and 0, and requires:
  - the sharing run shared (summary.json stress_shared_point_steps > 0; the other 0), so the test
    cannot pass by never sharing;
  - summary.json equal in every value but the timings and the share counter;
  - monitor.csv equal, row for row, digit for digit;
  - the last particle output equal, field for field and particle for particle.

Usage: verify_stress_share.py --burst build/burst --deck DECK [--ranks 2] [--extra "..."]
"""
import argparse
import atexit
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
TIMING = ("second", "wall", "stress_shared_point_steps")


def run(burst, deck, ranks, extra):
    out = tempfile.mkdtemp(prefix="burst_share_")
    atexit.register(shutil.rmtree, out, True)
    cmd = [*MPIEXEC, "-n", str(ranks), burst, "-options_file", os.path.join(ROOT, deck), "-output_dir", out, "-progress", "false", *extra]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-4000:] + proc.stderr[-4000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    with open(os.path.join(out, "summary.json")) as f:
        return out, json.load(f)


def differences(a, b, path=""):
    """The paths where two JSON values differ, timings left out."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            if any(t in k for t in TIMING):
                continue
            if k not in a or k not in b:
                out.append(f"{path}/{k} (in one only)")
            else:
                out += differences(a[k], b[k], f"{path}/{k}")
        return out
    return [] if a == b else [f"{path}: {a} against {b}"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--deck", required=True)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--extra", default="", help="more burst options for both runs")
    args = p.parse_args()
    extra = args.extra.split()
    out_on, on = run(args.burst, args.deck, args.ranks, extra + ["-mpm_stress_share", "1"])
    out_off, off = run(args.burst, args.deck, args.ranks, extra + ["-mpm_stress_share", "0"])
    failures = []
    shared, steps, particles = on["stress_shared_point_steps"], on["steps"], on.get("particles", 0)
    print(f"{args.deck} on {args.ranks} ranks: {steps} steps; {shared} point-steps updated on another rank with sharing, "
          f"{off['stress_shared_point_steps']} without")
    if not (shared > 0 and off["stress_shared_point_steps"] == 0):
        failures.append("the sharing run did not share, or the other did")
    diff = differences(on, off)
    print(f"  summary.json: {len(diff)} values differ (timings left out) {'OK' if not diff else 'FAIL'}")
    for d in diff[:10]:
        print(f"    {d}")
    if diff:
        failures.append("summary.json differs")
    with open(os.path.join(out_on, "monitor.csv")) as f_on, open(os.path.join(out_off, "monitor.csv")) as f_off:
        rows_on, rows_off = f_on.read().splitlines(), f_off.read().splitlines()
    same = rows_on == rows_off
    print(f"  monitor.csv: {len(rows_on)} rows, {'identical OK' if same else 'differ FAIL'}")
    if not same:
        failures.append("monitor.csv differs")
    last_on = sorted(glob.glob(os.path.join(out_on, "particles_*.h5")))
    last_off = sorted(glob.glob(os.path.join(out_off, "particles_*.h5")))
    if not last_on or len(last_on) != len(last_off):
        failures.append("no particle output to compare")
    else:
        with h5py.File(last_on[-1], "r") as a, h5py.File(last_off[-1], "r") as b:
            names = []
            a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) else None)
            bad = [n for n in names if n not in b or not np.array_equal(a[n][()], b[n][()])]
        print(f"  {os.path.basename(last_on[-1])}: {len(names)} datasets, {len(bad)} differ {'OK' if not bad else 'FAIL ' + ', '.join(bad[:5])}")
        if bad or not names:
            failures.append("particle output differs")
    if failures:
        print("FAIL: " + "; ".join(failures))
        sys.exit(1)
    print("PASS")


if __name__ == "__main__":
    main()
