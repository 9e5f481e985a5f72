#!/usr/bin/python3
"""Benchmarks; they report figures and never fail on time.
  particle step: a 2-D and a 3-D elastic block with each interpolator on 1 and 2 ranks: particle-steps
                 per second per core (stepping wall time from summary.json, without setup and output)
                 and bytes of swarm storage per particle.
  stress update: the same 3-D block (cpGIMP) with 4340 steel, the ns per particle of the stress update
                 (MPM_Stress event of -log_view) and of the whole step, for Johnson-Cook + von Mises and
                 for the paper's full 4340 set, and beside them PBX 9501 with ViscoSCRAM (a 1 cm block,
                 so that the step is the exploding scenes') (--stress-only).
  Taylor impact: the 3-D Taylor impact step (tests/decks/taylor3d.opts: OFHC copper, Johnson-Cook +
                 Mie-Gruneisen, 0.5 mm cells, 8 particles per cell, rigid anvil with frictionless
                 contact, MUSL, cpGIMP, a fixed number of steps): ns per particle-step and bytes per
                 particle.
  gas (--ice):   scripts/bench_ice.py: the semi-implicit pressure preconditioners and the gas
                 cell-updates per second per core (1 and 4 gases, 2-D and 3-D, explicit and
                 semi-implicit); --ice-only runs just that.
  comparison (--compare REV): builds commit REV beside the working tree (git archive into
                 build-compare/<sha>/, Release, reused when it exists) and runs it and --burst
                 alternately (A B B A ...) on the same cases, --repeats times; prints per case the
                 speed-up ratio (REV's time / this tree's time, > 1 means this tree is faster; on
                 one rank the phase's share of the process CPU time, see run_case) as
                 median [min, max] over the pairs, both sides' bytes per particle, and the relative
                 difference of the final kinetic and internal energies (a check that the answers agree).
                 Cases: --cases (default: every one of COMPARE_CASES).
Usage: scripts/bench.py --burst build/burst [--quick] [--stress-only] [--ice | --ice-only]
       scripts/bench.py --burst build/burst --compare e5aecdf [--repeats 5] [--cases taylor3d,block2d_linear]"""
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


def run_burst(binary, ranks, options):
    """One run on `ranks` ranks in a scratch output folder; returns (summary.json, the finished process)."""
    with tempfile.TemporaryDirectory() as out:
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [binary, *options, "-output_dir", out]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            print(proc.stdout[-2000:], proc.stderr[-2000:])
            raise SystemExit(f"benchmark run failed: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f), proc


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--burst", required=True)
    p.add_argument("--quick", action="store_true", help="small sizes (for a smoke test)")
    p.add_argument("--shapes", default="linear,ugimp,cpgimp,bspline2")
    p.add_argument("--ranks", default="1,2")
    p.add_argument("--stress-only", action="store_true", help="only the stress-update benchmark")
    p.add_argument("--ice", action="store_true", help="also the gas (ICE) benchmarks of scripts/bench_ice.py")
    p.add_argument("--ice-only", action="store_true", help="only the gas (ICE) benchmarks")
    p.add_argument("--compare", metavar="REV", help="compare against commit REV, built beside the working tree")
    p.add_argument("--compare-binary", metavar="PATH", help="with --compare: use this already built burst as REV's binary")
    p.add_argument("--repeats", type=int, default=5, help="pairs of runs per case in --compare (default 5)")
    p.add_argument("--cases", default=None, help="comma-separated cases of --compare (default: all): " + ",".join(c[0] for c in COMPARE_CASES))
    p.add_argument("--taylor-steps", type=int, default=100, help="steps of the Taylor impact case (default 100)")
    args = p.parse_args()
    if args.compare:
        compare(args)
        return
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
                s, _ = run_burst(args.burst, ranks, ["-options_file", deck, *extra])
                rate = s["particle_steps_per_second_per_core"]
                rows.append(dict(dim=dim, shape=shape, ranks=ranks, particles=s["particles"], rate=rate, bytes=s["bytes_per_particle"]))
                print(f"{dim:>3} {shape:>9} {ranks:>5} {s['particles']:>10} {s['steps']:>5} {rate / 1e6:>19.2f} {1e9 / rate:>12.1f} {s['bytes_per_particle']:>10}")
    with open(os.path.join(ROOT, "build", "bench.json") if os.path.isdir(os.path.join(ROOT, "build")) else os.devnull, "w") as f:
        json.dump(rows, f, indent=1)
    stress_benchmark(args)
    taylor_benchmark(args)
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
# The reactant beside the metals: PBX 9501 with ViscoSCRAM (options/materials/pbx9501_viscoscram.opts),
# the same block scaled to 1 cm (40^3 cells of 0.25 mm, radial velocity 5 m/s: 1250 /s in tension, so
# the cracks grow) so that the step, about 4e-8 s, is that of the exploding scenes (lambda_5 dt < 0.5:
# no sub-steps); replaces the steel file and geometry of STRESS_SETS. (label, material file, material, options)
STRESS_SETS_REACTANT = [
    ("PBX 9501 ViscoSCRAM (5 Maxwell elements + crack)", "options/materials/pbx9501_viscoscram.opts", "pbx",
     ["-grid_upper", "0.01,0.01,0.01", "-block_lower", "0.001,0.001,0.001", "-block_upper", "0.009,0.009,0.009", "-block_center", "0.005,0.005,0.005",
      "-block_radial_velocity", "5"]),
]


def stress_benchmark(args):
    n = 12 if args.quick else 40
    steps = 5 if args.quick else 15
    deck = os.path.join(ROOT, "tests/decks/bench_block.opts")
    print(f"stress update, 3-D cpGIMP block of 4340 steel expanding radially at 500 m/s (plastic everywhere), {n}^3 cells, 8 particles per cell, 1 rank:")
    # the reactant's block (STRESS_SETS_REACTANT) keeps the steel material defined but unused, so the
    # deck's steel options are read; its own file and geometry come after the steel's
    runs = [(label, extra, False) for label, extra in STRESS_SETS]
    runs += [(label, ["-options_file", os.path.join(ROOT, material_file), "-materials", f"steel,{name}", "-block_material", name, *extra], True)
             for label, material_file, name, extra in STRESS_SETS_REACTANT]

    def run(extra, max_steps):
        """(particles, steps, MPM_Stress seconds, particle-steps per second), or the reason it failed"""
        with tempfile.TemporaryDirectory() as out:
            cmd = [args.burst, "-options_file", deck, "-options_file", os.path.join(ROOT, "options/materials/steel_4340_jc.opts"), "-block_material", "steel",
                   "-output_dir", out, "-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", f"{n},{n},{n}", "-block_lower", "0.1,0.1,0.1",
                   "-block_upper", "0.9,0.9,0.9", "-block_velocity", "0,0,0", "-block_center", "0.5,0.5,0.5", "-block_radial_velocity", "500",
                   "-mpm_outside_domain", "remove", "-mpm_shape_type", "cpgimp", "-max_steps", str(max_steps), "-log_view",
                   "-options_allow_unused", *extra]  # the block deck's linear_elastic moduli are not read by the 4340 file's model
            proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
            if proc.returncode:
                return next((line.split("ERROR:", 1)[1].strip() for line in (proc.stdout + proc.stderr).splitlines() if "PETSC ERROR:" in line and ("Unknown" in line or "not" in line)), "run failed")
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
        stress_time = next(float(line.split()[3]) for line in proc.stdout.splitlines() if line.startswith("MPM_Stress"))
        return s["particles"], s["steps"], stress_time, s["particle_steps_per_second"]

    for label, extra, marginal in runs:
        r = run(extra, steps)
        if isinstance(r, str):
            print(f"  {label}: not available ({r})")
            continue
        particles, nsteps, stress_time, rate = r
        line = f"  {label}: {particles} particles, stress update {1e9 * stress_time / (particles * nsteps):.0f} ns, whole particle-step {1e9 / rate:.0f} ns"
        if marginal:  # the first step loads every crack from rest (sub-steps); the steps after it, from a run of twice as many steps
            r2 = run(extra, 2 * steps)
            if not isinstance(r2, str):
                line += f"; each further step {1e9 * (r2[2] - stress_time) / (particles * (r2[1] - nsteps)):.0f} ns"
        print(line)


def taylor_args(steps):
    return ["-options_file", os.path.join(ROOT, "tests/decks/taylor3d.opts"), "-max_steps", str(steps)]


def taylor_benchmark(args):
    steps = 10 if args.quick else args.taylor_steps
    for ranks in [int(r) for r in args.ranks.split(",")]:
        s, _ = run_burst(args.burst, ranks, taylor_args(steps))
        print(f"3-D Taylor impact step (copper, JC + Mie-Gruneisen, rigid anvil, MUSL, cpGIMP), {ranks} rank(s): {s['particles']} particles, "
              f"{s['steps']} steps, {1e9 / s['particle_steps_per_second_per_core']:.0f} ns per particle-step per core, {s['bytes_per_particle']} bytes per particle")


# ---------------------------------------------------------------------------------------------------
# Comparison mode: this tree's burst (A) against a build of commit REV (B), alternately.
BLOCK = "tests/decks/bench_block.opts"
BLOCK3D = ["-final_time", "1", "-dim", "3", "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", "64,64,64", "-block_lower", "0.1,0.1,0.1",
           "-block_upper", "0.9,0.9,0.9", "-block_velocity", "20,10,5", "-max_steps", "15"]
STRESS = ["-options_file", BLOCK, "-options_file", "options/materials/steel_4340_jc.opts", "-block_material", "steel", "-dim", "3",
          "-grid_lower", "0,0,0", "-grid_upper", "1,1,1", "-grid_cells", "40,40,40", "-block_lower", "0.1,0.1,0.1", "-block_upper", "0.9,0.9,0.9",
          "-block_velocity", "0,0,0", "-block_center", "0.5,0.5,0.5", "-block_radial_velocity", "500", "-mpm_outside_domain", "remove",
          "-mpm_shape_type", "cpgimp", "-max_steps", "15", "-final_time", "1", "-log_view"]
# (name, description, ranks, arguments (paths relative to the working tree), metric): metric "step" is the
# stepping time of summary.json, "stress" the MPM_Stress event of -log_view, "wall" the whole run (as
# CPU time on one rank: see run_case).
COMPARE_CASES = [
    ("block2d_linear", "2-D elastic block, linear, 512^2 cells, 672 400 particles, 30 steps", 1,
     ["-options_file", BLOCK, "-grid_cells", "512,512", "-mpm_shape_type", "linear", "-max_steps", "30", "-final_time", "1"], "step"),
    ("block3d_cpgimp", "3-D elastic block, cpGIMP, 64^3 cells, 15 steps", 1, ["-options_file", BLOCK, *BLOCK3D, "-mpm_shape_type", "cpgimp"], "step"),
    ("block3d_bspline", "3-D elastic block, B-spline, 64^3 cells, 15 steps", 1, ["-options_file", BLOCK, *BLOCK3D, "-mpm_shape_type", "bspline2"], "step"),
    ("taylor3d", "3-D Taylor impact step (copper JC + MG, rigid anvil, MUSL, cpGIMP), 100 steps", 1, ["-options_file", "tests/decks/taylor3d.opts", "-max_steps", "100", "-final_time", "8e-5"], "step"),
    ("taylor3d_2ranks", "the same on 2 ranks", 2, ["-options_file", "tests/decks/taylor3d.opts", "-max_steps", "100", "-final_time", "8e-5"], "step"),
    ("stress_jc", "stress update alone, JC + von Mises (hypoelastic EOS), 3-D block of 4340, 15 steps", 1, [*STRESS, *STRESS_SETS[0][1]], "stress"),
    ("stress_4340", "stress update alone, the paper's full 4340 set, 15 steps", 1, [*STRESS, *STRESS_SETS[1][1]], "stress"),
    ("cylinder2d", "prescribed-pressure cylinder scene (4340, cylinder2d_4340.opts; its lattice form on 160 x 160 cells, as in every recorded comparison), whole run to 20 us", 1,
     ["-options_file", "options/scenes/cylinder2d_4340.opts", "-wall_seeding", "lattice", "-grid_upper", "0.12,0.12", "-grid_cells", "160,160", "-final_time", "2e-5",
      "-output_interval", "0", "-output_grid", "false", "-fragments", "false",
      "-progress", "false"], "wall"),
]


def build_revision(rev):
    """Builds commit rev (Release) in build-compare/<sha>/ beside the working tree; returns the binary."""
    import time
    sha = subprocess.run(["git", "rev-parse", "--verify", rev + "^{commit}"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    base = os.path.join(ROOT, "build-compare", sha[:12])
    binary = os.path.join(base, "build", "burst")
    if os.path.exists(binary):
        return sha, binary
    src = os.path.join(base, "src")
    os.makedirs(src, exist_ok=True)
    archive = subprocess.Popen(["git", "archive", sha], cwd=ROOT, stdout=subprocess.PIPE)
    subprocess.run(["tar", "-x", "-C", src], stdin=archive.stdout, check=True)
    archive.wait()
    print(f"building {rev} ({sha[:12]}) in {base} ...", flush=True)
    t0 = time.time()
    log = open(os.path.join(base, "build.log"), "w")
    subprocess.run(["cmake", "-S", src, "-B", os.path.join(base, "build"), "-DCMAKE_BUILD_TYPE=Release"], stdout=log, stderr=subprocess.STDOUT, check=True)
    subprocess.run(["cmake", "--build", os.path.join(base, "build"), "-j", str(os.cpu_count() or 2), "--target", "burst"], stdout=log, stderr=subprocess.STDOUT, check=True)
    print(f"  built in {time.time() - t0:.0f} s", flush=True)
    return sha, binary


def run_case(binary, ranks, case_args, metric):
    """One run: returns (seconds, summary dict). The machine is shared, so on one rank the phase's
    time is its share of the process's CPU time: CPU seconds (user + sys, which do not grow while
    the process waits for a core) times the phase's wall time over the process's wall time. On
    several ranks the CPU time includes MPI's busy waiting, so the phase's wall time is used."""
    import resource
    import time
    # older commits (e5aecdf) spell -max_steps and -final_time with the mpm_ prefix: give both, and
    # let a tree that refuses unused options take the spelling it does not know as a warning
    aliases = {"-max_steps": "-mpm_max_steps", "-final_time": "-mpm_final_time"}
    case_args = list(case_args) + [x for i, a in enumerate(case_args) if a in aliases for x in (aliases[a], case_args[i + 1])] + ["-options_allow_unused"]
    with tempfile.TemporaryDirectory() as out:
        cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [binary, *case_args, "-output_dir", out]
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        if proc.returncode:
            print(proc.stdout[-2000:], proc.stderr[-2000:])
            raise SystemExit(f"benchmark run failed: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    if metric == "stress":
        phase = next(float(line.split()[3]) for line in proc.stdout.splitlines() if line.startswith("MPM_Stress"))
    elif metric == "wall":
        phase = wall
    else:
        phase = s["wall_time_s"]
    return (cpu * phase / wall if ranks == 1 else phase), s


def compare(args):
    import statistics
    if args.compare_binary:
        sha, other = args.compare, os.path.abspath(args.compare_binary)
    else:
        sha, other = build_revision(args.compare)
    names = args.cases.split(",") if args.cases else [c[0] for c in COMPARE_CASES]
    cases = [c for c in COMPARE_CASES if c[0] in names]
    unknown = set(names) - {c[0] for c in cases}
    if unknown:
        raise SystemExit(f"unknown case(s) {', '.join(sorted(unknown))}; valid: {', '.join(c[0] for c in COMPARE_CASES)}")
    head = subprocess.run(["git", "describe", "--always", "--dirty"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    print(f"burst comparison on {cpu_name()}, {os.cpu_count()} cores: A = {args.burst} (working tree {head}), B = {args.compare} ({sha[:12]})")
    print(f"speed-up = B's time / A's time per pair, {args.repeats} pairs run alternately (A B, then B A); median [min, max]")
    results = []
    for name, label, ranks, case_args, metric in cases:
        ta, tb = [], []
        for r in range(args.repeats):
            order = [("A", args.burst), ("B", other)] if r % 2 == 0 else [("B", other), ("A", args.burst)]
            for side, binary in order:
                t, s = run_case(binary, ranks, case_args, metric)
                (ta if side == "A" else tb).append((t, s))
        ratios = sorted(b[0] / a[0] for a, b in zip(ta, tb))
        sa, sb = ta[-1][1], tb[-1][1]
        def rel(key):
            x, y = sa.get(key, 0.0), sb.get(key, 0.0)
            return abs(x - y) / max(abs(x), abs(y), 1e-300)
        # every other value of summary.json (energies, momentum, mass, plastic work, counts, ...), so
        # that "the answers agree" covers more than two energies: 0 means bitwise the same figures
        timing = {"wall_time_s", "particle_steps_per_second", "particle_steps_per_second_per_core", "bytes_per_particle", "stress_shared_point_steps"}
        def values(d):
            out = []
            for key, value in sorted(d.items()):
                if key in timing:
                    continue
                for i, x in enumerate(value if isinstance(value, list) else [value]):
                    if isinstance(x, (int, float)) and not isinstance(x, bool):
                        out.append(((key, i), float(x)))
            return out
        va, vb = dict(values(sa)), dict(values(sb))
        summary_diff = max([abs(va[k] - vb[k]) / max(abs(va[k]), abs(vb[k]), 1e-300) for k in va if k in vb] or [0.0])
        row = dict(case=name, label=label, ranks=ranks, metric=metric, particles=sa["particles"], steps=sa["steps"],
                   time_a=statistics.median(t for t, _ in ta), time_b=statistics.median(t for t, _ in tb),
                   speedup=statistics.median(ratios), speedup_min=ratios[0], speedup_max=ratios[-1],
                   bytes_a=sa.get("bytes_per_particle"), bytes_b=sb.get("bytes_per_particle"),
                   kinetic_diff=rel("kinetic_energy"), internal_diff=rel("internal_energy"), summary_diff=summary_diff)
        results.append(row)
        unit = {"step": "stepping", "stress": "stress update", "wall": "whole run"}[metric] + (" CPU" if ranks == 1 else " wall")
        print(f"{name:>16}: speed-up {row['speedup']:.3f} [{row['speedup_min']:.3f}, {row['speedup_max']:.3f}]  ({unit} {row['time_a']:.3f} s vs {row['time_b']:.3f} s; "
              f"{row['particles']} particles, {ranks} rank(s); bytes/particle {row['bytes_a']} vs {row['bytes_b']}; "
              f"energies differ by {row['kinetic_diff']:.1e} (kinetic), {row['internal_diff']:.1e} (internal), every summary value by at most {summary_diff:.1e})", flush=True)
    if os.path.isdir(os.path.join(ROOT, "build")):
        with open(os.path.join(ROOT, "build", f"bench_compare_{sha[:12]}.json"), "w") as f:
            json.dump(dict(machine=cpu_name(), cores=os.cpu_count(), a=head, b=sha, results=results), f, indent=1)


if __name__ == "__main__":
    main()
