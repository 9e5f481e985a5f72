#!/usr/bin/python3
"""A jet on part of an inflow face (-ice_inflow_<face>_jet, src/ice/setup.cxx ReadInflowJet,
boundary.cxx, advection.cxx; deck tests/decks/jet_inlet.opts: a 1800 K, 10 m/s slot in a 300 K,
1 m/s coflow on the floor of a box of air). Each subcommand runs burst, prints its measured figures
with a verdict (`name: value (tol X) OK|FAIL`) and exits non-zero on failure; ctest calls them
(tests/CMakeLists.txt, block 4f).

  inflow  one run (--ranks, --extra): the mass in through the face (summary.json budget.mass
          open_faces_by_face) equals t sum_cells rho_c v_c A of each face cell's own state (the jet's
          where the cell centre is within the radius of the centre, else the coflow's), to --tol; the
          budgets close (mass, momentum, energy, and the faces' masses add up to the open faces'); in
          the first row of cells above the face the temperature is the jet's (more than halfway from
          the coflow's) over the slot and the coflow's (within 2 % of the difference) two cells and
          more beside it. A jet that is ignored, or given to the wrong cells, fails all three.
  ranks   the deck on 1 and on 2 ranks (the box splits across the face, through the slot): every gas
          field and every face's mass the same to --tol.
Usage: verify_inflow_jet.py --burst build/burst inflow|ranks [--deck D] [--extra "..."] [--ranks N] [--tol T]
"""
import argparse
import os
import shlex
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify_coupling import run, scratch, options  # noqa: E402
from verify import check, finish  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FACES = {"xmin": (0, 0), "xmax": (0, 1), "ymin": (1, 0), "ymax": (1, 1)}


def deck_options(args):
    """The deck's options with --extra's on top ("-name value" pairs)."""
    opts = options(args.deck)
    extra = shlex.split(args.extra)
    for i, word in enumerate(extra):
        if word.startswith("-") and not word[1:2].isdigit():
            opts[word] = extra[i + 1] if i + 1 < len(extra) and not (extra[i + 1].startswith("-") and not extra[i + 1][1:2].isdigit()) else "true"
    return opts


def floats(text):
    return [float(v) for v in text.split(",")]


def face_cells(opts, face):
    """Per face cell (2-D): its centre along the face, and the state (rho, velocity (2), T) the deck
    gives it; the face's direction and the cell area A (per unit depth)."""
    d, _ = FACES[face]
    lower, upper, cells = floats(opts["-grid_lower"]), floats(opts["-grid_upper"]), [int(c) for c in opts["-grid_cells"].split(",")]
    e = 1 - d  # the direction along the face
    h = [(upper[k] - lower[k]) / cells[k] for k in range(2)]
    coflow = floats(opts[f"-ice_inflow_{face}"])
    jet = floats(opts[f"-ice_inflow_{face}_jet"])
    radius = float(opts[f"-ice_inflow_{face}_jet_radius"])
    center = floats(opts[f"-ice_inflow_{face}_jet_center"])[e] if f"-ice_inflow_{face}_jet_center" in opts else 0.5 * (lower[e] + upper[e])
    x = lower[e] + (np.arange(cells[e]) + 0.5) * h[e]
    in_jet = np.abs(x - center) <= radius
    states = np.where(in_jet[:, None], np.array(jet)[None, :], np.array(coflow)[None, :])
    return d, x, in_jet, states, h[e], center, radius, coflow, jet, h


def last_gas(out):
    name = sorted(f for f in os.listdir(out) if f.startswith("gas_") and f.endswith(".h5"))[-1]
    with h5py.File(os.path.join(out, name), "r") as f:
        return name, {k: np.asarray(f["cells"][k]) for k in f["cells"]}


def inflow(args):
    failures = []
    opts = deck_options(args)
    face = args.face
    d, x, in_jet, states, area, center, radius, coflow, jet, h = face_cells(opts, face)
    out = scratch()
    s = run(args.burst, args.deck, out, shlex.split(args.extra), ranks=args.ranks)
    t = s["final_time"]
    m = s["budget"]["mass"]
    sign = 1 if FACES[face][1] == 0 else -1  # the normal velocity that flows in
    rate = float(np.sum(states[:, 0] * sign * states[:, 1 + d]) * area)  # kg/s (per m of depth)
    rate_coflow = len(x) * coflow[0] * sign * coflow[1 + d] * area
    expected, measured = rate * t, -m["open_faces_by_face"][face]
    print(f"{os.path.basename(args.deck)} {args.extra}: {s['steps']} steps to t = {t:.6g} s on {args.ranks} rank(s); jet {jet} over"
          f" |x - {center:g}| <= {radius:g} m ({int(in_jet.sum())} of {len(x)} face cells), coflow {coflow}")
    print(f"  mass in through {face}: {measured:.15g} kg/m, expected t sum rho v A = {expected:.15g} kg/m"
          f" (the coflow alone would give {rate_coflow * t:.6g})")
    check(f"mass in through {face} against each cell's state (relative)", abs(measured - expected) / expected, args.tol, failures)
    by_face = sum(m["open_faces_by_face"].values())
    check("faces' masses against the open faces' (relative)", abs(by_face - m["open_faces"]) / max(abs(m["open_faces"]), 1e-300), args.tol, failures)
    for b in ("mass", "momentum", "energy"):
        check(f"{b} budget error (of its largest term)", abs(s["budget"][b]["error"]), args.tol, failures)
    # the hot jet just above the face: the first row of cells
    name, f = last_gas(out)
    gas = opts["-ice_materials"].split(",")[0]
    T = f[f"{gas}_temperature"][0]  # [Ny][Nx]
    row = T[0 if FACES[face][1] == 0 else -1, :] if d == 1 else T[:, 0 if FACES[face][1] == 0 else -1]
    dT = jet[-1] - coflow[-1]
    beside = np.abs(x - center) >= radius + 2 * h[1 - d]
    inside = (row[in_jet] - coflow[-1]) / dT
    outside = np.abs(row[beside] - coflow[-1]) / abs(dT)
    print(f"  {name}, first row above {face}: T over the slot {row[in_jet].min():.1f}-{row[in_jet].max():.1f} K,"
          f" two cells and more beside it {row[beside].min():.1f}-{row[beside].max():.1f} K (jet {jet[-1]:g} K, coflow {coflow[-1]:g} K)")
    check("over the slot, 1/2 - least (T - T_coflow)/(T_jet - T_coflow)", 0.5 - inside.min(), 0.0, failures, fmt="{:+.3f}")
    check("beside the slot, largest |T - T_coflow|/|T_jet - T_coflow|", outside.max(), 0.02, failures)
    finish(f"inflow_jet[{face}, {args.ranks} rank(s)]", failures)


def ranks(args):
    failures = []
    runs = []
    for n in (1, 2):
        out = scratch()
        s = run(args.burst, args.deck, out, shlex.split(args.extra), ranks=n)
        runs.append((s, *last_gas(out)))
    (s1, n1, f1), (s2, n2, f2) = runs
    if n1 != n2 or sorted(f1) != sorted(f2):
        finish("inflow_jet ranks", [f"outputs differ: {n1} {sorted(f1)} / {n2} {sorted(f2)}"])
    print(f"{os.path.basename(args.deck)} {args.extra}: {s1['steps']} / {s2['steps']} steps on 1 / 2 ranks, {n1}")
    for k in sorted(f1):
        check(f"{k}: max |1 rank - 2 ranks| / max |{k}|", np.abs(f1[k] - f2[k]).max() / max(np.abs(f1[k]).max(), 1e-300), args.tol, failures)
    a, b = s1["budget"]["mass"]["open_faces_by_face"], s2["budget"]["mass"]["open_faces_by_face"]
    scale = max(abs(v) for v in a.values())
    for face in a:
        print(f"  mass out through {face}: {a[face]:.15g} / {b[face]:.15g} kg/m")
        check(f"{face} mass, |1 rank - 2 ranks| / largest face's", abs(a[face] - b[face]) / scale, args.tol, failures)
    finish("inflow_jet ranks", failures)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("check", choices=["inflow", "ranks"])
    p.add_argument("--deck", default="tests/decks/jet_inlet.opts")
    p.add_argument("--face", default="ymin", choices=sorted(FACES))
    p.add_argument("--extra", default="")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--tol", type=float, default=1e-12)
    args = p.parse_args()
    {"inflow": inflow, "ranks": ranks}[args.check](args)


if __name__ == "__main__":
    main()
