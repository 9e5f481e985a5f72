#!/usr/bin/python3
"""Benchmark of the particle step: a 2-D and a 3-D elastic block with each interpolator on 1 and 2
ranks. Prints particle-steps per second per core (from the stepping wall time in summary.json, i.e.
without setup and output) and bytes of swarm storage per particle. Reports figures; never fails on
time. Usage: scripts/bench.py --burst build/burst [--quick]"""
import argparse
import json
import os
import platform
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1", "--bind-to", "core"]


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--burst", required=True)
    p.add_argument("--quick", action="store_true", help="small sizes (for a smoke test)")
    p.add_argument("--shapes", default="linear,ugimp,cpgimp,bspline2")
    p.add_argument("--ranks", default="1,2")
    args = p.parse_args()
    sizes = {2: (64 if args.quick else 512), 3: (16 if args.quick else 64)}
    steps = {2: 10 if args.quick else 30, 3: 5 if args.quick else 15}
    deck = os.path.join(ROOT, "tests/decks/bench_block.opts")
    print(f"burst benchmark on {cpu_name()}, {os.cpu_count()} cores")
    print(f"{'dim':>3} {'shape':>9} {'ranks':>5} {'particles':>10} {'steps':>5} {'Mpart-steps/s/core':>19} {'ns/part-step':>12} {'bytes/part':>10}")
    rows = []
    for dim in (2, 3):
        n = sizes[dim]
        for shape in args.shapes.split(","):
            for ranks in [int(r) for r in args.ranks.split(",")]:
                extra = ["-mpm_shape_type", shape, "-mpm_max_steps", str(steps[dim])]
                if dim == 2:
                    extra += ["-grid_cells", f"{n},{n}"]
                else:
                    extra += ["-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", f"{n},{n},{n}",
                              "-block_lower", "0.1,0.1,0.1", "-block_upper", "0.9,0.9,0.9", "-block_velocity", "20,10,5"]
                with tempfile.TemporaryDirectory() as out:
                    cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [args.burst, "-options_file", deck, "-output_dir", out, *extra]
                    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
                    if proc.returncode:
                        print(proc.stdout[-2000:], proc.stderr[-2000:])
                        raise SystemExit(f"benchmark run failed: {' '.join(cmd)}")
                    with open(os.path.join(out, "summary.json")) as f:
                        s = json.load(f)
                rate = s["particle_steps_per_second_per_core"]
                rows.append(dict(dim=dim, shape=shape, ranks=ranks, particles=s["particles"], rate=rate, bytes=s["bytes_per_particle"]))
                print(f"{dim:>3} {shape:>9} {ranks:>5} {s['particles']:>10} {s['steps']:>5} {rate / 1e6:>19.2f} {1e9 / rate:>12.1f} {s['bytes_per_particle']:>10}")
    with open(os.path.join(ROOT, "build", "bench.json") if os.path.isdir(os.path.join(ROOT, "build")) else os.devnull, "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
