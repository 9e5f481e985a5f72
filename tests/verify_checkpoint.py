#!/usr/bin/python3
"""Checkpoint and restart (issue 11; src/io/checkpoint.cxx). Each subcommand runs real option files
through burst, interrupts and continues them, and compares with the uninterrupted run.

  same     run to N uninterrupted; run to K with a checkpoint, restart to N on the same ranks: every
           particle field, every gas cell field, monitor.csv, the xmf series and summary.json are
           bit-identical
  ranks    the same with the restart on another number of ranks (1 -> 2, 2 -> 1): particles matched
           by id and gas fields agree to --tol (round-off of the summation order)
  signal   SIGUSR1 / SIGTERM (or -max_wall_time) during a run: a checkpoint, a clean stop (exit 0) with
           a message, and the restart reaches the uninterrupted answer bit for bit
  wallint  -checkpoint_wall_interval: a run writes checkpoints by the clock (two or more, at increasing
           steps); a restart from the oldest reaches the same last step bit for bit (particle fields and
           the summary energies, mass and step count)
  kill     SIGKILL while a checkpoint is being written (held open with -checkpoint_debug_delay): the
           previous checkpoint and snapshots are intact and the restart reaches the uninterrupted answer
  bad      a missing, truncated or mismatched checkpoint stops with a message naming the file and what
           does not match; an unwritable -output_dir stops at start-up
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
SKIP_SUMMARY = {"wall_time_s", "particle_steps_per_second", "particle_steps_per_second_per_core", "ranks",
                "stress_shared_point_steps"}  # timings, and what follows them: the points sent depend on the measured cost of sending one


def command(args, deck, out, extra, ranks):
    return ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [args.burst, "-options_file", deck, "-output_dir", out, "-progress", "false", *extra]


def run(args, deck, out, extra=(), ranks=1, expect_rc=0):
    cmd = command(args, deck, out, extra, ranks)
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
    if expect_rc is not None and proc.returncode != expect_rc:
        sys.stdout.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"FAIL: burst exited with {proc.returncode}: {' '.join(cmd)}")
    return proc


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def h5_arrays(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return out


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        s = {k: v for k, v in json.load(f).items() if k not in SKIP_SUMMARY}
    for v in s.values():  # wall-clock rates of the gas block
        if isinstance(v, dict):
            for k in [k for k in v if "per_second" in k]:
                del v[k]
    return s


def read(out, name):
    with open(os.path.join(out, name)) as f:
        return f.read()


def outputs(out, step):
    return [n for n in (f"particles_{step:06d}.h5", f"gas_{step:06d}.h5") if os.path.exists(os.path.join(out, n))]


def compare_identical(ref, got, step, failures):
    """Bit-identical: every dataset of the last outputs, monitor.csv, the xmf series, summary.json."""
    names = outputs(ref, step)
    if not names:
        failures.append(f"no output at step {step}")
    for name in names:
        a, b = h5_arrays(os.path.join(ref, name)), h5_arrays(os.path.join(got, name))
        differ = [k for k in a if k not in b or a[k].shape != b[k].shape or not np.array_equal(a[k], b[k])]
        print(f"  {name}: {len(a)} datasets, {len(differ)} differ {'OK' if not differ else 'FAIL ' + ', '.join(differ[:5])}")
        if differ:
            failures.append(name)
    for name in ("monitor.csv", "particles.xmf", "gas.xmf"):
        if os.path.exists(os.path.join(ref, name)):
            same = read(ref, name) == read(got, name)
            print(f"  {name} identical: {'OK' if same else 'FAIL'}")
            if not same:
                failures.append(name)
    sa, sb = summary(ref), summary(got)
    differ = [k for k in sa if sa[k] != sb.get(k)]
    print(f"  summary.json: {len(differ)} entries differ {'OK' if not differ else 'FAIL ' + ', '.join(differ)}")
    if differ:
        failures.append("summary.json")


def compare_close(ref, got, step, tol, failures):
    """Round-off: particles matched by id, gas cells by position; relative to each field's scale."""
    worst = 0.0
    for name in outputs(ref, step):
        a, b = h5_arrays(os.path.join(ref, name)), h5_arrays(os.path.join(got, name))
        if "particles/id" in a:
            ia, ib = np.argsort(a["particles/id"]), np.argsort(b["particles/id"])
            if not np.array_equal(a["particles/id"][ia], b["particles/id"][ib]):
                failures.append(f"{name}: particle ids differ")
                continue
            a = {k: (v[ia] if k.startswith("particles/") else v) for k, v in a.items()}
            b = {k: (v[ib] if k.startswith("particles/") else v) for k, v in b.items()}
        for k in a:
            scale = max(np.max(np.abs(a[k])), 1e-300)
            err = float(np.max(np.abs(a[k] - b[k]))) / scale if a[k].size else 0.0
            worst = max(worst, err)
    ok = worst <= tol
    print(f"  largest relative difference over all fields: {worst:.3e} (tol {tol:g}) {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("fields")
    sa, sb = summary(ref), summary(got)
    for key in ("kinetic_energy", "internal_energy", "mass", "steps"):
        if key in sa:
            err = abs(sa[key] - sb[key]) / max(abs(sa[key]), 1e-300)
            print(f"  summary {key}: relative difference {err:.3e}")
            if err > tol:
                failures.append(key)


def finish(test, failures):
    if failures:
        print(f"{test}: FAIL ({', '.join(failures)})")
        sys.exit(1)
    print(f"{test}: OK")


def interrupted(args, base, ranks_a, ranks_b, tag, failures):
    """Uninterrupted to N on ranks_a; to K with checkpoints on ranks_a, restart to N on ranks_b. The
    restart must say it restarted from the step-K checkpoint: a run that ignored -restart would reach
    the same answer from step 0."""
    extra = ["-output_interval", str(args.k), "-monitor_interval", "5", *args.extra.split()]
    ref = fresh(os.path.join(base, f"{tag}_ref"))
    run(args, args.deck, ref, [*extra, "-max_steps", str(args.n)], ranks_a)
    got = fresh(os.path.join(base, f"{tag}_restart"))
    run(args, args.deck, got, [*extra, "-max_steps", str(args.k), "-checkpoint_interval", str(args.k)], ranks_a)
    proc = run(args, args.deck, got, [*extra, "-max_steps", str(args.n), "-restart", got], ranks_b)
    line = [l for l in proc.stdout.splitlines() if l.startswith("Restarted from")]
    expected = f"checkpoint_{args.k:06d}.h5"
    ok = bool(line) and expected in line[0]
    print(f"  {line[0] if line else 'no restart message'}: from {expected} {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append(f"no restart from {expected}")
    return ref, got


def same(args):
    failures = []
    print(f"same: {args.deck}, {args.n} steps vs {args.k} + restart, {args.ranks} rank(s)")
    ref, got = interrupted(args, args.out, args.ranks, args.ranks, f"same_np{args.ranks}", failures)
    compare_identical(ref, got, args.n, failures)
    finish("checkpoint_same", failures)


def ranks(args):
    failures = []
    a, b = [int(x) for x in args.ranks_from_to.split(",")]
    print(f"ranks: {args.deck}, {args.n} steps on {a} rank(s) vs {args.k} on {a} + restart on {b}")
    ref, got = interrupted(args, args.out, a, b, f"ranks_{a}to{b}", failures)
    compare_close(ref, got, args.n, args.tol, failures)
    finish("checkpoint_ranks", failures)


def wait_for(path, text, proc, seconds=120):
    end = time.time() + seconds
    while time.time() < end:
        if proc.poll() is not None:
            return False
        if os.path.exists(path) and text in open(path).read():
            return True
        time.sleep(0.05)
    return False


def signal_test(args):
    """A run stopped by a signal (or the wall-clock budget) checkpoints, exits 0 and restarts exactly.

    The signalled run is given far more steps than it can take before the signal arrives (a fast
    machine once finished the whole run first and the signal hit it in PetscFinalize); the reference
    and the restart then run to a step past the one where it stopped."""
    failures = []
    extra = ["-output_interval", str(args.k), "-monitor_interval", "1", *args.extra.split()]
    got = fresh(os.path.join(args.out, f"signal_{args.signal}"))
    log = os.path.join(got, "log.txt")
    stop_extra = ["-final_time", "1e30", *(["-max_wall_time", "4"] if args.signal == "wall" else [])]
    with open(log, "w") as f:
        proc = subprocess.Popen(command(args, args.deck, got, [*extra, *stop_extra, "-mpm_dt", args.slow_dt, "-max_steps", "100000000"], args.ranks), cwd=ROOT, stdout=f, stderr=subprocess.STDOUT)
        if args.signal != "wall":
            # a few monitor lines first (the run is in its step loop), then the signal
            if not wait_for(os.path.join(got, "monitor.csv"), "\n3,", proc):
                failures.append("run ended before the signal")
            proc.send_signal(signal.SIGUSR1 if args.signal == "usr1" else signal.SIGTERM)
        rc = proc.wait(timeout=300)
    text = open(log).read()
    stop = [l for l in text.splitlines() if l.startswith("Stopping at step")]
    print(f"  exit code {rc}; {stop[0] if stop else 'no stop message'}")
    if rc != 0 or not stop:
        sys.stdout.write(text[-3000:])
        finish(f"checkpoint_signal_{args.signal}", failures + ["clean stop"])
    step = int(stop[0].split()[3].rstrip(","))
    if not os.path.exists(os.path.join(got, f"checkpoint_{step:06d}.h5")):
        failures.append("checkpoint missing")
    if args.signal == "wall":  # check the message and the checkpoint only
        ok = "-max_wall_time" in stop[0]
        print(f"  message names -max_wall_time: {'OK' if ok else 'FAIL'}")
        finish("checkpoint_signal_wall", failures if ok else failures + ["message"])
        return
    last = (step // args.k + 2) * args.k  # an output step past the stop
    print(f"  stopped at step {step}; reference and restart to step {last}")
    ref = fresh(os.path.join(args.out, f"signal_{args.signal}_ref"))
    run(args, args.deck, ref, [*extra, *stop_extra, "-mpm_dt", args.slow_dt, "-max_steps", str(last)], args.ranks)
    run(args, args.deck, got, [*extra, *stop_extra, "-mpm_dt", args.slow_dt, "-max_steps", str(last), "-restart", got], args.ranks)
    compare_identical(ref, got, last, failures)
    finish(f"checkpoint_signal_{args.signal}", failures)


def wall_interval(args):
    failures = []
    # a quiet machine runs the deck faster: lengthen the run until the clock has written two checkpoints
    for attempt in range(4):
        extra = ["-output_interval", str(args.n), "-monitor_interval", "100", "-mpm_dt", args.slow_dt, *args.extra.split()]
        ref = fresh(os.path.join(args.out, "wallint"))
        run(args, args.deck, ref, [*extra, "-max_steps", str(args.n), "-checkpoint_wall_interval", "0.5", "-checkpoint_keep", "1000"], args.ranks)
        steps = sorted(int(n[len("checkpoint_"):-len(".h5")]) for n in os.listdir(ref) if n.startswith("checkpoint_") and n.endswith(".h5"))
        print(f"  {args.n} steps: checkpoints by the clock at steps {steps}")
        if len(steps) >= 2:
            break
        args.n *= 3
    if len(steps) < 2:
        finish("checkpoint_wall_interval", ["fewer than two checkpoints: the run was too fast for the 0.5 s interval even at --n " + str(args.n)])
    got = fresh(os.path.join(args.out, "wallint_restart"))
    first = os.path.join(got, f"checkpoint_{steps[0]:06d}.h5")
    shutil.copy(os.path.join(ref, f"checkpoint_{steps[0]:06d}.h5"), first)
    run(args, args.deck, got, [*extra, "-max_steps", str(args.n), "-restart", first], args.ranks)
    compare_close(ref, got, args.n, 0.0, failures)
    finish("checkpoint_wall_interval", failures)


def kill_test(args):
    failures = []
    extra = ["-output_interval", str(args.k), "-monitor_interval", "5", *args.extra.split()]
    ref = fresh(os.path.join(args.out, "kill_ref"))
    run(args, args.deck, ref, [*extra, "-max_steps", str(3 * args.k)])
    got = fresh(os.path.join(args.out, "kill"))
    run(args, args.deck, got, [*extra, "-max_steps", str(args.k), "-checkpoint_interval", str(args.k)])
    before = open(os.path.join(got, f"checkpoint_{args.k:06d}.h5"), "rb").read()
    log = os.path.join(got, "log.txt")
    with open(log, "w") as f:
        cmd = command(args, args.deck, got, [*extra, "-max_steps", str(3 * args.k), "-checkpoint_interval", str(args.k), "-checkpoint_debug_delay", "60", "-restart", got], 1)
        proc = subprocess.Popen(cmd, cwd=ROOT, stdout=f, stderr=subprocess.STDOUT)
        held = wait_for(log, "renaming in", proc)
        proc.kill()  # SIGKILL while checkpoint_<2k> is written but not yet renamed
        proc.wait()
    print(f"  killed while writing checkpoint_{2 * args.k:06d}: {'OK' if held else 'FAIL (never reached the write)'}")
    if not held:
        failures.append("kill timing")
    intact = open(os.path.join(got, f"checkpoint_{args.k:06d}.h5"), "rb").read() == before
    absent = not os.path.exists(os.path.join(got, f"checkpoint_{2 * args.k:06d}.h5"))
    print(f"  previous checkpoint intact: {'OK' if intact else 'FAIL'}; the interrupted one not visible under its name: {'OK' if absent else 'FAIL'}")
    if not (intact and absent):
        failures.append("checkpoint files")
    snapshot = h5_arrays(os.path.join(got, f"particles_{2 * args.k:06d}.h5"))  # the output before the kill is whole
    print(f"  snapshot particles_{2 * args.k:06d}.h5 readable: {len(snapshot)} datasets OK")
    proc = run(args, args.deck, got, [*extra, "-max_steps", str(3 * args.k), "-restart", got])
    if f"checkpoint_{args.k:06d}.h5" not in proc.stdout:
        failures.append("restart did not use the previous checkpoint")
    compare_identical(ref, got, 3 * args.k, failures)
    finish("checkpoint_kill", failures)


def bad(args):
    failures = []
    base = fresh(os.path.join(args.out, "bad"))
    disks, ring = "options/scenes/colliding_disks.opts", "options/scenes/ring2d.opts"
    good = os.path.join(base, "disks")
    run(args, disks, good, ["-max_steps", "2", "-checkpoint_interval", "2"])
    cp = os.path.join(good, "checkpoint_000002.h5")
    ring_dir = os.path.join(base, "ring")
    run(args, ring, ring_dir, ["-max_steps", "1", "-checkpoint_interval", "1"])
    truncated = os.path.join(base, "truncated.h5")
    with open(cp, "rb") as f:
        data = f.read()
    with open(truncated, "wb") as f:
        f.write(data[: len(data) // 2])
    empty = fresh(os.path.join(base, "empty"))
    not_a_folder = os.path.join(base, "not_a_folder")  # (root writes through permissions, so a file stands in)
    open(not_a_folder, "w").close()
    ring_cells = "-grid_cells 60,60"
    for line in open(os.path.join(ROOT, ring)):
        if line.startswith("-grid_cells"):
            ring_cells = line.split("#")[0].strip()
    cases = [
        ("missing file", disks, ["-restart", os.path.join(base, "nothing.h5")], "Option -restart .*nothing.h5: no such file or folder"),
        ("folder without checkpoints", disks, ["-restart", empty], "holds no checkpoint_<step>.h5"),
        ("truncated", disks, ["-restart", truncated], "Checkpoint .*truncated.h5 cannot be read as HDF5 \\(truncated or damaged\\)"),
        ("other grid", disks, ["-restart", cp, "-grid_cells", "40,40"], "Checkpoint .*checkpoint_000002.h5 does not match this run: 20 cells in direction 0, this run has 40"),
        ("other scene", disks, ["-restart", cp, "-scene", "other"], "does not match this run: its scene \\(-scene\\) is 'colliding_disks', this run's is 'other'"),
        ("other materials", disks, ["-restart", ring_dir, "-scene", "ring2d", *ring_cells.split(), "-grid_lower", "0,0", "-grid_upper", "0.07,0.07",
                                    "-lower_center", "0.02,0.02", "-upper_center", "0.05,0.05", "-lower_radius", "0.01", "-upper_radius", "0.01"],
         "does not match this run: its solid material set \\(-materials\\) is 'steel', this run's is 'disk'"),
        ("unwritable output", disks, ["-max_steps", "1", "-output_dir", not_a_folder], "Option -output_dir .*not_a_folder: the folder cannot be written"),
    ]
    import re
    for name, deck, extra, pattern in cases:
        out = fresh(os.path.join(base, "run_" + name.replace(" ", "_")))
        cmd = [args.burst, "-options_file", deck, "-output_dir", out, *extra]
        if name == "unwritable output":
            cmd = [args.burst, "-options_file", deck, *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=120)
        text = proc.stdout + proc.stderr
        ok = proc.returncode != 0 and re.search(pattern, text) is not None
        print(f"  {name}: exit {proc.returncode}, message {'OK' if ok else 'FAIL'}")
        if not ok:
            sys.stdout.write("\n".join(l for l in text.splitlines() if "ERROR" in l and "Configure" not in l)[:2000] + "\n")
            failures.append(name)
    finish("checkpoint_bad", failures)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("check", choices=["same", "ranks", "signal", "wallint", "kill", "bad"])
    p.add_argument("--burst", required=True)
    p.add_argument("--deck", default="options/scenes/ring2d.opts")
    p.add_argument("--out", default="checkpoint_tests")
    p.add_argument("--n", type=int, default=40, help="steps of the whole run")
    p.add_argument("--k", type=int, default=20, help="step of the checkpoint")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--ranks-from-to", default="1,2")
    p.add_argument("--tol", type=float, default=1e-10)
    p.add_argument("--signal", choices=["usr1", "term", "wall"], default="usr1")
    p.add_argument("--slow-dt", default="1e-9", help="a small -mpm_dt for the wall-clock test (many steps)")
    p.add_argument("--extra", default="")
    args = p.parse_args()
    args.out = os.path.join(os.path.abspath(args.out), os.environ.get("BURST_CHECKPOINT_TEST", args.check))  # parallel tests apart
    os.makedirs(args.out, exist_ok=True)
    {"same": same, "ranks": ranks, "signal": signal_test, "wallint": wall_interval, "kill": kill_test, "bad": bad}[args.check](args)


if __name__ == "__main__":
    main()
