#!/usr/bin/python3
"""Benchmarks; they report figures and never fail on time.
  particle step: a 2-D and a 3-D elastic block with each interpolator on 1 and 2 ranks: particle-steps
                 per second per core (stepping wall time from summary.json, without setup and output)
                 and bytes of swarm storage per particle.
  stress update: the same 3-D block (cpGIMP) with 4340 steel, the ns per particle of the stress update
                 (MPM_Stress event of -log_view) and of the whole step, for Johnson-Cook + von Mises and
                 for the paper's full 4340 set (--stress).
  gas (--ice):   scripts/bench_ice.py: the semi-implicit pressure preconditioners and the gas
                 cell-updates per second per core (1 and 4 gases, 2-D and 3-D, explicit and
                 semi-implicit); --ice-only runs just that.
Usage: scripts/bench.py --burst build/burst [--quick] [--stress-only] [--ice | --ice-only]"""
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
    p.add_argument("--stress-only", action="store_true", help="only the stress-update benchmark")
    p.add_argument("--ice", action="store_true", help="also the gas (ICE) benchmarks of scripts/bench_ice.py")
    p.add_argument("--ice-only", action="store_true", help="only the gas (ICE) benchmarks")
    args = p.parse_args()
    if args.ice_only:
        ice_benchmark(args)
        return
    if args.stress_only:
        stress_benchmark(args)
        return
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
                extra = ["-mpm_shape_type", shape, "-max_steps", str(steps[dim])]
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
    stress_benchmark(args)
    if args.ice:
        ice_benchmark(args)


def ice_benchmark(args):
    """The gas figures: scripts/bench_ice.py in this process (same --burst, --quick)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("bench_ice", os.path.join(ROOT, "scripts", "bench_ice.py"))
    bench_ice = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench_ice)
    bench_ice.main(["--burst", args.burst] + (["--quick"] if args.quick else []))


# Material sets of the stress-update benchmark: options added to the 4340 file.
STRESS_SETS = [
    ("JC + von Mises, hypoelastic", ["-steel_eos_type", "hypoelastic"]),
    ("paper's 4340 set (MG, JC, GTN, JC damage, porosity, Drucker + Becker)",
     ["-steel_yield_type", "gtn", "-steel_damage_type", "johnson_cook", "-steel_damage_D1", "0.05", "-steel_damage_D2", "3.44", "-steel_damage_D3", "-2.12",
      "-steel_damage_D4", "0.002", "-steel_damage_D5", "0.61", "-steel_porosity_growth", "true", "-steel_porosity_nucleation", "true",
      "-steel_porosity_initial_mean", "0.005", "-steel_porosity_initial_deviation", "0.001", "-steel_damage_initial_mean", "0.01",
      "-steel_damage_initial_deviation", "0.005", "-steel_stability_types", "drucker,becker", "-steel_failure_criteria", "melt,tepla,stability"]),
]


def stress_benchmark(args):
    n = 12 if args.quick else 40
    steps = 5 if args.quick else 15
    deck = os.path.join(ROOT, "tests/decks/bench_block.opts")
    print(f"stress update, 3-D cpGIMP block of 4340 steel expanding radially at 500 m/s (plastic everywhere), {n}^3 cells, 8 particles per cell, 1 rank:")
    for label, extra in STRESS_SETS:
        with tempfile.TemporaryDirectory() as out:
            cmd = [args.burst, "-options_file", deck, "-options_file", os.path.join(ROOT, "options/materials/steel_4340_jc.opts"), "-block_material", "steel",
                   "-output_dir", out, "-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", f"{n},{n},{n}", "-block_lower", "0.1,0.1,0.1",
                   "-block_upper", "0.9,0.9,0.9", "-block_velocity", "0,0,0", "-block_center", "0.5,0.5,0.5", "-block_radial_velocity", "500",
                   "-mpm_outside_domain", "remove", "-mpm_shape_type", "cpgimp", "-max_steps", str(steps), "-log_view", *extra]
            proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
            if proc.returncode:
                reason = next((line.split("ERROR:", 1)[1].strip() for line in (proc.stdout + proc.stderr).splitlines() if "PETSC ERROR:" in line and ("Unknown" in line or "not" in line)), "run failed")
                print(f"  {label}: not available ({reason})")
                continue
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
        stress_time = next(float(line.split()[3]) for line in proc.stdout.splitlines() if line.startswith("MPM_Stress"))
        per_update = 1e9 * stress_time / (s["particles"] * s["steps"])
        per_step = 1e9 / s["particle_steps_per_second"]
        plastic = next((line for line in proc.stdout.splitlines() if line.startswith("MPM_Stress")), "")
        print(f"  {label}: {s['particles']} particles, stress update {per_update:.0f} ns, whole particle-step {per_step:.0f} ns")


if __name__ == "__main__":
    main()
