#!/usr/bin/python3
"""-<name>_seeding polar: rings about the centre instead of the grid's sub-cell lattice. Read from the
particles written at t = 0 (particles_000000.h5):
  2-D (cylinder2d_4340's quarter annulus at --cells): the volumes add up to the annulus' area to
      round-off (the lattice's staircase misses it by about a percent); every particle lies inside the
      annulus, on rings spaced (b - a)/n_r with n_r = round((b - a)/(h/ppc)); the points of a ring are
      evenly spaced in angle and half a spacing from the sector's edges.
  The bore's pressure: a half annulus (-90 to 90 degrees) in free space under a constant pressure p
      on its inner surface; after one step the x momentum is p a dt times the midpoint rule's sum of
      cos(theta) over the inner ring, 2 (dtheta/2)/sin(dtheta/2), to 1e-10: the inner ring's areas
      add up to the bore's arc (the lattice's staircase misses it by a few %).
  3-D (exploding_cylinder3d: wall annulus, cap and charge cylinders, all polar): each object's volume
      is its exact volume to round-off.
  --ranks 2: the same particles (ids and positions) as one rank.
"""
import argparse
import os
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from verify import check, finish, monitor, run  # noqa: E402

A, B = 0.0508, 0.05715  # the wall's inner and outer radii (m)


def lround(x):
    """C's lround (halves away from zero), as seed.cxx counts rings and points; Python's round() halves to even."""
    return int(np.floor(x + 0.5))


def seed(burst, deck, extra, ranks=1):
    """The particles at t = 0 (-max_steps 0)."""
    with tempfile.TemporaryDirectory() as out:
        run(burst, deck, out, ["-max_steps", "0", *extra], ranks=ranks)
        with h5py.File(os.path.join(out, "particles_000000.h5")) as f:
            p = f["particles"]
            return {k: p[k][:] for k in ("coordinates", "volume", "id", "material")}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--cells", type=int, default=40)
    p.add_argument("--ppc", type=int, default=3)
    p.add_argument("--ranks", type=int, default=1)
    args = p.parse_args()
    failures = []
    deck2 = "options/scenes/cylinder2d_4340.opts"
    base = ["-grid_upper", "0.12,0.12", "-grid_cells", f"{args.cells},{args.cells}", "-wall_particles_per_cell", str(args.ppc)]
    area = np.pi / 4 * (B * B - A * A)
    polar = seed(args.burst, deck2, base + ["-wall_seeding", "polar"])
    lattice = seed(args.burst, deck2, base + ["-wall_seeding", "lattice"])
    x, vol = polar["coordinates"], polar["volume"]
    r, theta = np.hypot(x[:, 0], x[:, 1]), np.arctan2(x[:, 1], x[:, 0])
    print(f"cylinder2d_4340, {args.cells} cells, {args.ppc} x {args.ppc}: {len(vol)} polar particles (lattice {len(lattice['volume'])})")
    check("polar: |sum of volumes - annulus area| / area", abs(vol.sum() - area) / area, 1e-12, failures)
    print(f"  (the lattice's staircase: {abs(lattice['volume'].sum() - area) / area:.3e})")
    check("polar: the farthest particle outside the annulus (m)", max(0.0, (A - r).max(), (r - B).max()), 0.0, failures)
    h = 0.12 / args.cells
    nr = max(1, lround((B - A) / (h / args.ppc)))
    radii = A + (np.arange(nr) + 0.5) * (B - A) / nr
    ring = np.abs(r[:, None] - radii[None, :]).argmin(axis=1)
    check("polar: |r - nearest ring radius| (m)", np.abs(r - radii[ring]).max(), 1e-12 * B, failures)
    worst = 0.0
    for k in range(nr):
        t = np.sort(theta[ring == k])
        dt = (np.pi / 2) / len(t)
        worst = max(worst, np.abs(t - (np.arange(len(t)) + 0.5) * dt).max())
    check("polar: |theta - (k + 1/2) dtheta| on every ring (rad)", worst, 1e-12, failures)
    if args.ranks > 1:
        two = seed(args.burst, deck2, base + ["-wall_seeding", "polar"], ranks=args.ranks)
        o1, o2 = np.argsort(polar["id"]), np.argsort(two["id"])
        same_ids = len(o1) == len(o2) and np.array_equal(polar["id"][o1], two["id"][o2])
        print(f"  {args.ranks} ranks: {len(o2)} particles, the same ids: {same_ids}")
        if not same_ids:
            failures.append(f"{args.ranks} ranks seed other particles")
        else:
            check(f"{args.ranks} ranks: max |x - x(1 rank)| (m)", np.abs(x[o1] - two["coordinates"][o2]).max(), 0.0, failures)
    # the pressure on the bore, one step from rest
    impulse = {}
    for arrangement in ("polar", "lattice"):
        with tempfile.TemporaryDirectory() as out:
            run(args.burst, deck2, out, ["-wall_seeding", arrangement, "-wall_angle_range", "-90,90", "-grid_lower", "-0.1,-0.1", "-grid_upper", "0.1,0.1",
                                         "-grid_cells", "80,80", "-wall_particles_per_cell", "2", "-bc_xmin", "free", "-bc_ymin", "free", "-gas_time", "0,1",
                                         "-gas_value", "1e8,1e8", "-max_steps", "1", "-monitor_interval", "1"])
            row = {k: v[-1] for k, v in monitor(out).items()}
        impulse[arrangement] = float(row["momentum_x"]) / (1e8 * A * float(row["time"]))
    spacing = 0.2 / 80 / 2
    r_inner = A + 0.5 * (B - A) / max(1, lround((B - A) / spacing))
    dtheta = np.pi / max(1, lround(r_inner * np.pi / spacing))
    expected = 2 * (dtheta / 2) / np.sin(dtheta / 2)
    print(f"  one step of 1e8 Pa on the bore of a half annulus: x momentum / (p a dt) = {impulse['polar']:.12f} polar, {impulse['lattice']:.6f} lattice, "
          f"midpoint rule {expected:.12f}")
    check("polar: |x impulse / (p a dt) - midpoint rule| / midpoint rule", abs(impulse["polar"] - expected) / expected, 1e-10, failures)
    # 3-D: three objects, each polar
    deck3 = "options/scenes/exploding_cylinder3d.opts"
    s3 = seed(args.burst, deck3, ["-grid_cells", "10,10,15", "-wall_seeding", "polar", "-cap_seeding", "polar", "-charge_seeding", "polar"])
    z = s3["coordinates"][:, 2]
    exact = {"wall": np.pi / 4 * (B * B - A * A) * 0.1, "cap": np.pi / 4 * B * B * 0.00635, "charge": np.pi / 4 * A * A * 0.1}
    steel, charge = s3["material"] == 0, s3["material"] == 1
    got = {"wall": s3["volume"][steel & (z < 0.1)].sum(), "cap": s3["volume"][steel & (z > 0.1)].sum(), "charge": s3["volume"][charge].sum()}
    for name in exact:
        check(f"3-D polar {name}: |sum of volumes - exact| / exact", abs(got[name] - exact[name]) / exact[name], 1e-12, failures)
    finish("verify_polar_seeding", failures)


if __name__ == "__main__":
    main()
