#!/usr/bin/python3
"""Checks on the whole gas field (gas_NNNNNN.h5, every cell):
  symmetry  the 2-D cylindrical blast on the quarter (options/scenes/blast2d.opts) stays symmetric
            about the diagonal: p, density, temperature equal under x <-> y, u_x(x, y) = u_y(y, x),
            to round-off (issue 7: "the 2-D blast stays symmetric about the diagonal")
  ranks     a deck run on 1 and on 2 MPI ranks gives the same fields to round-off (2-D and 3-D)
Each prints its measured value against its tolerance and exits 1 on failure.
Usage: verify_gas_fields.py --burst build/burst symmetry|ranks [--deck D] [--extra "..."] [--tol T]"""
import argparse
import os
import shlex
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]


def run(args, out, ranks):
    cmd = [args.burst, "-options_file", os.path.join(ROOT, args.deck), "-output_dir", out, "-progress", "false"] + shlex.split(args.extra)
    if ranks > 1:
        cmd = MPIEXEC + ["-n", str(ranks)] + cmd
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode:
        print(p.stdout[-2000:], p.stderr[-4000:])
        raise SystemExit(f"FAIL: burst exited with {p.returncode}: {' '.join(cmd)}")


def last_fields(out):
    files = sorted(f for f in os.listdir(out) if f.startswith("gas_") and f.endswith(".h5"))
    with h5py.File(os.path.join(out, files[-1]), "r") as h:
        return files[-1], {k: np.asarray(h["cells"][k]) for k in h["cells"]}


def symmetry(args):
    with tempfile.TemporaryDirectory() as out:
        run(args, out, args.ranks)
        name, f = last_fields(out)
        worst, failures = 0.0, []
        for k, v in f.items():
            v = v[0]  # 2-D: [1][Ny][Nx](...)
            scale = max(np.abs(v).max(), 1e-300)
            if v.ndim == 2:
                err = np.abs(v - v.T).max() / scale
            else:  # vectors padded to 3: u_x(x, y) against u_y(y, x)
                err = max(np.abs(v[:, :, 0] - v[:, :, 1].T).max(), np.abs(v[:, :, 1] - v[:, :, 0].T).max()) / scale
            print(f"  {k}: max asymmetry about the diagonal / max |{k}| = {err:.3e}")
            worst = max(worst, err)
        ok = worst <= args.tol
        print(f"symmetry[{os.path.basename(args.deck)}, {name}]: worst {worst:.3e} (tol {args.tol:g}) {'OK' if ok else 'FAIL'}")
        return 0 if ok else 1


def ranks(args):
    with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
        run(args, a, 1)
        run(args, b, 2)
        na, fa = last_fields(a)
        nb, fb = last_fields(b)
        if na != nb or sorted(fa) != sorted(fb):
            print(f"FAIL: outputs differ in name or fields: {na} {sorted(fa)} / {nb} {sorted(fb)}")
            return 1
        worst = 0.0
        for k in sorted(fa):
            err = np.abs(fa[k] - fb[k]).max() / max(np.abs(fa[k]).max(), 1e-300)
            print(f"  {k}: max |1 rank - 2 ranks| / max |{k}| = {err:.3e}")
            worst = max(worst, err)
        ok = worst <= args.tol
        print(f"ranks[{os.path.basename(args.deck)}, {na}]: worst {worst:.3e} (tol {args.tol:g}) {'OK' if ok else 'FAIL'}")
        return 0 if ok else 1


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("check", choices=["symmetry", "ranks"])
    p.add_argument("--deck", default="options/scenes/blast2d.opts")
    p.add_argument("--extra", default="")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--tol", type=float, default=1e-12)
    args = p.parse_args()
    args.burst = os.path.abspath(args.burst)
    return symmetry(args) if args.check == "symmetry" else ranks(args)


if __name__ == "__main__":
    sys.exit(main())
