#!/usr/bin/python3
"""The set-up's memory estimate (src/memory.hpp) against the memory a run takes.

Runs each case for one step with -info, takes the estimates the set-up printed (the grid, the gas)
plus the particles' (particles x 1.7 x bytes_per_particle of summary.json), and compares their sum
with the run's peak resident memory (getrusage of the child) minus that of a tiny run (the
libraries). The estimate refuses runs that do not fit, so it must neither miss much (a run that
passes then dies in an allocation) nor overshoot much (a run that fits is refused): the ratio must
lie in [--low, --high] (default [0.75, 1.33]).
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from verify import check, finish  # noqa: E402

CASES = [
    ("exploding cylinder 2-D, 400 x 400", "options/scenes/exploding_cylinder2d.opts", ["-grid_cells", "400,400"]),
    ("Taylor rod 3-D, 4 x 4 x 4 per cell", "options/scenes/taylor.opts", ["-dim", "3", "-taylor_particles_per_cell", "4"]),
    ("blast 2-D gas, 800 x 800", "options/scenes/blast2d.opts", ["-grid_cells", "800,800"]),
]
PARTICLE_FACTOR = 1.7  # kMemoryParticleFactor


def peak_rss(cmd):
    """(peak resident bytes of the child, its stdout): one child per call, so RUSAGE_CHILDREN's max is its own
    only if it exceeds the earlier ones: each case runs in a fresh python child."""
    code = ("import resource, subprocess, sys; p = subprocess.run(sys.argv[1:], capture_output=True, text=True); "
            "sys.stdout.write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024) + '\\n' + p.stdout + p.stderr); sys.exit(p.returncode)")
    proc = subprocess.run([sys.executable, "-c", code, *cmd], cwd=ROOT, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    first, _, rest = proc.stdout.partition("\n")
    return float(first), rest


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--low", type=float, default=0.75)
    p.add_argument("--high", type=float, default=1.33)
    args = p.parse_args()
    failures = []
    with tempfile.TemporaryDirectory() as out:
        base, _ = peak_rss([args.burst, "-options_file", "options/scenes/colliding_disks.opts", "-max_steps", "1", "-output_dir", out, "-output_interval", "0", "-progress", "false"])
    print(f"baseline (libraries, a tiny run): {base / 1e6:.0f} MB")
    for name, deck, extra in CASES:
        with tempfile.TemporaryDirectory() as out:
            rss, log = peak_rss([args.burst, "-options_file", deck, *extra, "-max_steps", "1", "-output_dir", out, "-output_interval", "0",
                                 "-progress", "false", "-info", ":sys"])
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
        parts = {m.group(1): float(m.group(2)) for m in re.finditer(r"Memory estimate for (.*?): ([0-9.e+]+) bytes", log)}
        particles = s.get("particles", 0) * PARTICLE_FACTOR * s.get("bytes_per_particle", 0)
        estimate = sum(parts.values()) + particles
        used = rss - base
        ratio = estimate / used
        print(f"{name}: estimate {estimate / 1e6:.0f} MB (" + ", ".join(f"{k}: {v / 1e6:.0f} MB" for k, v in parts.items())
              + f", {s.get('particles', 0)} particles: {particles / 1e6:.0f} MB); peak resident {rss / 1e6:.0f} MB less the baseline: {used / 1e6:.0f} MB; ratio {ratio:.3f}")
        check(f"{name}: |log(estimate / used)| against log of the bound", abs(__import__('math').log(ratio)),
              __import__('math').log(args.high if ratio > 1 else 1 / args.low), failures, fmt="{:.3f}")
    finish("memory", failures)


if __name__ == "__main__":
    main()
