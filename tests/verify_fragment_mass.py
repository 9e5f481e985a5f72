#!/usr/bin/python3
"""The base of -fragments_min_mass_fraction is the mass at t = 0. summary.json initial_mass must be the
seeded mass of the counted materials, whenever the first fragment search runs: ring2d (the 4340 ring
launched at 300 m/s) on a grid that ends just outside the ring, so that particles leave the domain
(-mpm_outside_domain remove) before the end, run with the search only at the end (-output_interval 0)
and at every step (-output_interval 1). The seeded mass is counted here from the lattice: the
sub-cell centres inside the annulus, each with density x sub-cell area.
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from verify import check, finish, run  # noqa: E402

DENSITY, INNER, OUTER = 7830.0, 0.0508, 0.05715  # ring2d.opts, steel_4340_paper.opts


def seeded_mass(cells, upper, ppc):
    h = upper / cells
    count = 0
    for i in range(cells * ppc):
        x = (i + 0.5) * h / ppc
        for j in range(cells * ppc):
            y = (j + 0.5) * h / ppc
            r = (x * x + y * y) ** 0.5
            count += INNER <= r <= OUTER
    return count * DENSITY * (h / ppc) ** 2


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--ranks", type=int, default=1)
    args = p.parse_args()
    cells, upper, ppc = 40, 0.0585, 2
    expected = seeded_mass(cells, upper, ppc)
    failures = []
    for interval in (0, 1):
        with tempfile.TemporaryDirectory() as out:
            s = run(args.burst, "options/scenes/ring2d.opts", out,
                    ["-grid_cells", f"{cells},{cells}", "-grid_upper", f"{upper},{upper}", "-ring_particles_per_cell", str(ppc), "-ring_seeding", "lattice",
                     "-final_time", "2e-5", "-output_interval", str(interval), "-output_grid", "false"], ranks=args.ranks)
        left = s["intact_mass"]
        print(f"ring2d, {cells} cells, -output_interval {interval}: initial_mass {s['initial_mass']:.9g} kg, seeded {expected:.9g} kg, "
              f"intact at the end {left:.6g} kg")
        # the run must lose mass, or the test could not tell t = 0 from the first search
        check(f"-output_interval {interval}: intact mass at the end / seeded mass < 0.99", left / expected, 0.99, failures)
        check(f"-output_interval {interval}: |initial_mass - seeded mass| / seeded mass", abs(s["initial_mass"] - expected) / expected, 1e-12, failures)
    finish("verify_fragment_mass", failures)


if __name__ == "__main__":
    main()
