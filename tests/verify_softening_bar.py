#!/usr/bin/python3
"""The 1-D softening bar of Bazant & Belytschko (1985) with burst's own softening (GTN void growth):
tests/decks/softening_bar.opts at 100, 200 and 400 cells over the 10 mm half bar (cell 0.1, 0.05,
0.025 mm; one square cell high between two symmetry faces, so the per-metre energies are divided by
the cell height to give J per m^2 of bar cross-section, which is also the crack area).

Measured at t = 3 us (4 us for the crack band, whose band must open fully), from the particle output:
  E  the energy dissipated per unit cross-section, (plastic work + failure energy) / h_y, J/m^2
  W  the width of the softening zone, the length of bar with plastic strain above 0.02 (five times
     the 0.004 the elastic-limit pulse leaves elsewhere), m

  none        without a length: W shrinks with the cell and E with it (no limit as h -> 0)
  nonlocal    -bar_regularization nonlocal, ell = 0.5 mm: W and E converge
  crack_band  -bar_regularization crack_band, G_f = 5 kJ/m^2, criterion f = 0.02: E converges
  parallel    nonlocal on 1 and 2 ranks (the average runs across the rank boundary): same answer

Each verdict line prints the measured number and the tolerance it is checked against.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify import check, finish  # noqa: E402  the verdict lines of every driver

DECK = os.path.join(ROOT, "tests", "decks", "softening_bar.opts")
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
HALF, RHO, STRAIN = 0.01, 7800.0, 0.02  # half bar (m), density, the zone's plastic-strain threshold
REGULARISATIONS = {
    "none": [],
    "nonlocal": ["-bar_regularization", "nonlocal", "-bar_regularization_length", "5e-4"],
    "crack_band": ["-bar_regularization", "crack_band", "-bar_fracture_energy", "5e3", "-bar_failure_porosity", "0.02", "-final_time", "4e-6"],
}


def run(burst, cells, extra, ranks=1):
    """Runs the bar at `cells` over the half bar (a square cell), returns (E, W, particles)."""
    h = HALF / cells
    with tempfile.TemporaryDirectory() as out:
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [
            burst, "-options_file", DECK, "-output_dir", out, "-grid_cells", f"{cells * 6 // 5},1", "-grid_upper", f"0.012,{h}",
            "-still_upper", f"0.006,{h}", "-flyer_upper", f"0.01,{h}", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            sys.stdout.write(proc.stdout[-3000:] + proc.stderr[-3000:])
            raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        last = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".h5"))[-1]
        with h5py.File(os.path.join(out, last), "r") as f:
            g = f["particles"]
            order = np.argsort(g["id"][...].ravel())
            p = {k: g[k][...][order].ravel() if g[k].ndim == 1 or g[k].shape[-1] == 1 else g[k][...][order] for k in ("id", "mass", "plastic_strain", "porosity")}
    energy = (s["plastic_work"] + s["failure_energy"]) / h
    width = np.sum(p["mass"][p["plastic_strain"] > STRAIN]) / (RHO * h)
    return energy, width, p


def convergence(args, which):
    failures, rows = [], []
    for cells in (100, 200, 400):
        e, w, _ = run(args.burst, cells, REGULARISATIONS[which])
        rows.append((cells, e, w))
        print(f"  {which}: {cells} cells (h {1e3 * HALF / cells:.3f} mm): E {e:.4e} J/m^2, W {1e3 * w:.3f} mm")
    (_, e1, w1), (_, e2, w2), (_, e3, w3) = rows
    if which == "none":
        # Without a length the zone is a cell or two (measured W 0.20, 0.10, 0.05 mm: halves with h)
        # and the energy falls with it (measured E 2.15e4, 1.95e4, 1.30e4 J/m^2). Checked: W at
        # 400 cells is at most 0.7 of W at 200 (a converging W would give 1), and E at 400 at
        # most 0.85 of E at 200 (measured 0.67): the mesh dependence is there to be cured.
        check("W(400)/W(200), no length (mesh dependence: <= 0.7)", w3 / w2, 0.7, failures, "{:.3f}")
        check("E(400)/E(200), no length (mesh dependence: <= 0.85)", e3 / e2, 0.85, failures, "{:.3f}")
    elif which == "nonlocal":
        # With ell = 0.5 mm (5, 10, 20 cells) the zone and the energy converge: measured W 0.600,
        # 0.575, 0.575 mm and E 2.055e4, 2.106e4, 2.131e4 J/m^2. Tolerances: 10 % on W between 200
        # and 400 cells (W counts particles, so it moves in steps of a particle, 0.025 mm at 200
        # cells = 4 %, and the kernel is the bell widened by two hats of h, 10 % of ell at 200
        # cells), 5 % on E between 200 and 400 (measured 1.2 %; 2.5 % between 100 and 200, so a
        # first-order approach leaves ~1 % to the limit). Without the length the same ratios are
        # 50 % and 33 % off (above), so the checks separate the two by a wide margin.
        check("|W(400)/W(200) - 1|, nonlocal (<= 0.10)", abs(w3 / w2 - 1), 0.10, failures, "{:.3f}")
        check("|E(400)/E(200) - 1|, nonlocal (<= 0.05)", abs(e3 / e2 - 1), 0.05, failures, "{:.3f}")
        check("|E(200)/E(100) - 1|, nonlocal (<= 0.10)", abs(e2 / e1 - 1), 0.10, failures, "{:.3f}")
        check("W(400), nonlocal, >= ell = 0.5 mm: 1 - W/ell (<= 0)", 1 - w3 / 5e-4, 0.0, failures, "{:.3f}")
    else:
        # The crack band fixes the energy, not the width: E per unit crack area converges
        # (measured 2.198e4, 2.013e4, 2.021e4 J/m^2: G_f = 5e3 in the band plus the pre-peak
        # plastic work, which converges too). 5 % between 200 and 400 cells (measured 0.4 %; the
        # 33 % of the unregularised bar would fail it); the coarse grid, where u_f = 2 G_f / sigma_i
        # = 20 um is only 0.4 of a 0.05 mm particle, is off by 9 % and not checked. The width is
        # not regularised by the crack band (measured 0.20, 0.35, 0.39 mm) and not checked.
        check("|E(400)/E(200) - 1|, crack band (<= 0.05)", abs(e3 / e2 - 1), 0.05, failures, "{:.3f}")
    finish(f"softening_bar {which}", failures)


def parallel(args):
    """Nonlocal on 1 and 2 ranks at 200 cells: the average crosses the rank boundary (x = 6 mm of
    the 12 mm grid, 10 cells of ghost nodes), so any error in the halo shows in the profile."""
    failures = []
    e1, w1, p1 = run(args.burst, 200, REGULARISATIONS["nonlocal"])
    e2, w2, p2 = run(args.burst, 200, REGULARISATIONS["nonlocal"], ranks=2)
    # Only the order of the P2G sums differs (src/mpm/nonlocal.cxx); the softening amplifies
    # round-off little over 500 steps: measured 1e-13 on the porosity.
    check("max |f(2 ranks) - f(1 rank)| (<= 1e-9)", float(np.max(np.abs(p2["porosity"] - p1["porosity"]))), 1e-9, failures)
    check("|E(2 ranks)/E(1 rank) - 1| (<= 1e-9)", abs(e2 / e1 - 1), 1e-9, failures)
    finish("softening_bar parallel", failures)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build", "burst"))
    p.add_argument("check", choices=["none", "nonlocal", "crack_band", "parallel"])
    args = p.parse_args()
    if args.check == "parallel":
        parallel(args)
    else:
        convergence(args, args.check)


if __name__ == "__main__":
    main()
