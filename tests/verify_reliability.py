#!/usr/bin/python3
"""Nothing lost, nothing silent (doc/running.md, Reliability): checkpoints that belong to their run,
one run per output folder, and option files that PETSc's reader would crash on or misread. Each
subcommand runs real option files through burst and checks files and messages.

  foreign     a fresh ring2d run (-checkpoint_interval 20, 60 steps) into a folder holding another
              run's checkpoints 40, 250 and 300 keeps its own (40, 60) and moves the other run's to
              other_runs/<run id>/ byte for byte, with a note; -restart on the folder continues it; a
              folder holding two runs' checkpoints is refused naming both; -restart with a file works
  lineage     a restart from checkpoint 10 of a folder holding 5, 10, 15, 20 with -checkpoint_keep 2
              keeps the checkpoints it writes (12 and 13 at the end), not the abandoned 15 and 20;
              -restart on the folder then continues from 13 (the newest written)
  corrupt     a checkpoint with one flipped bit (a sign, an exponent, a mantissa bit of a particle
              field) is refused naming the file and the checksum; -restart on its folder skips it with
              a note and continues from the older valid one
  options     a restart with a changed physics option is refused naming the option and both values;
              -restart_allow_option_change continues with a note; an output option may change freely
  legacy      a checkpoint without run id and checksum (an older burst's) is accepted with a note;
              one without a part's values (another version's layout) is refused, naming the part
  lock        one run per folder: --case live (a second run, also on 2 ranks, is refused naming the
              holder's host and pid; the first ends normally and removes the lock), stale (a dead
              pid's lock on this host, a live pid running another program, an old lock of another
              host: taken over with a note; a run stopped by an error removes its lock), fresh
              (another host's recent lock: refused), concurrent (two runs started at once: exactly one
              runs, the other is refused before writing)
  optionfile  --case self|pair|deep|nul|dangling: an option file that includes itself, two that
              include each other, a chain deeper than 16, a NUL byte, an -options_file with no file:
              refused before PETSc reads them, naming the files (the chain) and the line
"""
import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1"]
RING = "options/scenes/ring2d.opts"
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify_checkpoint import wait_for  # noqa: E402  (a line in a file, or the process ended)


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def burst(args, out, extra=(), deck=RING, ranks=1, wait=True):
    cmd = ([*MPIEXEC, "-n", str(ranks)] if ranks > 1 else []) + [args.burst, "-options_file", deck, "-output_dir", out, "-progress", "false", *extra]
    if not wait:
        return subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
    proc.text = proc.stdout + proc.stderr
    return proc


def checkpoints(out):
    return sorted(int(n[len("checkpoint_"):-len(".h5")]) for n in os.listdir(out) if re.fullmatch(r"checkpoint_\d+\.h5", n))


class Check:
    def __init__(self, name):
        self.name, self.failures = name, []

    def __call__(self, what, ok, text=""):
        print(f"  {what}: {'OK' if ok else 'FAIL'}")
        if not ok:
            self.failures.append(what)
            if text:
                keep = [l for l in text.splitlines() if ("ERROR" in l or "Note" in l) and "Configure options" not in l and not re.match(r"\[\d+\]PETSC ERROR: -", l)]
                sys.stdout.write("\n".join(keep)[:3000] + "\n")
        return ok

    def finish(self):
        if self.failures:
            print(f"{self.name}: FAIL ({'; '.join(self.failures)})")
            sys.exit(1)
        print(f"{self.name}: OK")


def refused(proc, pattern):
    return proc.returncode != 0 and re.search(pattern, proc.text, re.S) is not None


def foreign(args):
    check = Check("reliability_foreign")
    out = fresh(os.path.join(args.out, "folder"))
    other = fresh(os.path.join(args.out, "other"))
    p = burst(args, other, ["-max_steps", "6", "-checkpoint_interval", "3"])
    other_id = re.search(r"run ([0-9a-f]{16})", p.stdout).group(1)
    for a, b in ((3, 250), (6, 300)):  # another run's checkpoints, under the step numbers
        shutil.copy(os.path.join(other, f"checkpoint_{a:06d}.h5"), os.path.join(out, f"checkpoint_{b:06d}.h5"))
    shutil.copy(os.path.join(other, "checkpoint_000003.h5"), os.path.join(out, "checkpoint_000040.h5"))  # one whose name the run will write
    before = {s: open(os.path.join(out, f"checkpoint_{s:06d}.h5"), "rb").read() for s in (40, 250, 300)}
    p = burst(args, out, ["-max_steps", "60", "-checkpoint_interval", "20"])
    check("the fresh run exits 0", p.returncode == 0, p.text)
    aside = os.path.join(out, "other_runs", other_id)
    check("its start-up says where the other run's checkpoints went", re.search(rf"Note: -output_dir .* held checkpoints of another run \(run {other_id}\): checkpoint_000040\.h5, checkpoint_000250\.h5, checkpoint_000300\.h5; moved to .*other_runs/{other_id} \(continue that run with -restart", p.text) is not None, p.text)
    steps = checkpoints(out)
    print(f"  checkpoints in the folder: {steps}; in other_runs/{other_id}: {checkpoints(aside) if os.path.isdir(aside) else None}")
    check("its own newest two (40, 60) are kept", steps == [40, 60])
    check("the other run's 40, 250 and 300 are kept byte for byte (none overwritten by this run's 40)", os.path.isdir(aside) and all(open(os.path.join(aside, f"checkpoint_{s:06d}.h5"), "rb").read() == before[s] for s in (40, 250, 300)))
    p = burst(args, out, ["-max_steps", "62", "-checkpoint_interval", "2", "-restart", out])
    check("-restart on the folder continues this run from 60", p.returncode == 0 and re.search(r"Restarted from .*folder/checkpoint_000060\.h5", p.text) is not None, p.text)
    shutil.move(os.path.join(aside, "checkpoint_000300.h5"), os.path.join(out, "checkpoint_000300.h5"))  # two runs in one folder
    p = burst(args, out, ["-max_steps", "64", "-restart", out])
    check("-restart on a folder holding two runs is refused naming both", refused(p, rf"the folder holds the checkpoints of 2 runs: run [0-9a-f]{{16}} \(checkpoint_000062\.h5, checkpoint_000060\.h5\); run {other_id} \(checkpoint_000300\.h5\); name the checkpoint file"), p.text)
    p = burst(args, out, ["-max_steps", "64", "-restart", os.path.join(out, "checkpoint_000062.h5")])
    check("-restart with the file continues (the other run's checkpoint is moved aside again)", p.returncode == 0 and "checkpoint_000062.h5" in p.text and "moved to" in p.text, p.text)
    check.finish()


def lineage(args):
    check = Check("reliability_lineage")
    out = fresh(os.path.join(args.out, "folder"))
    p = burst(args, out, ["-max_steps", "20", "-checkpoint_interval", "5", "-checkpoint_keep", "100"])
    check("checkpoints 5, 10, 15, 20 written", checkpoints(out) == [5, 10, 15, 20], p.text)
    p = burst(args, out, ["-max_steps", "13", "-checkpoint_interval", "1", "-checkpoint_keep", "2", "-restart", os.path.join(out, "checkpoint_000010.h5")])
    steps = checkpoints(out)
    print(f"  after the restart from 10 to 13 with -checkpoint_keep 2: {steps}")
    check("the restart exits 0", p.returncode == 0, p.text)
    check("it keeps what it wrote (12, 13), not the abandoned 15 and 20", steps == [12, 13])
    p = burst(args, out, ["-max_steps", "14", "-restart", out])
    check("-restart on the folder continues from 13 (newest written)", p.returncode == 0 and "checkpoint_000013.h5" in p.text, p.text)
    check.finish()


def flip(path, dataset, index, bit):
    import h5py
    import numpy as np
    with h5py.File(path, "r+") as f:
        d = f[dataset]
        flat = d[()].reshape(-1).copy()
        bits = flat.view(np.uint64)
        bits[index] ^= np.uint64(1) << np.uint64(bit)
        d[...] = flat.reshape(d.shape)


def corrupt(args):
    check = Check("reliability_corrupt")
    out = fresh(os.path.join(args.out, "folder"))
    burst(args, out, ["-max_steps", "10", "-checkpoint_interval", "5"])
    cp = os.path.join(out, "checkpoint_000010.h5")
    pristine = open(cp, "rb").read()
    for name, dataset, bit in (("sign", "particles/velocity", 63), ("exponent", "particles/DMSwarmPIC_coor", 55), ("mantissa", "particles/mass", 3)):
        with open(cp, "wb") as f:
            f.write(pristine)
        try:
            flip(cp, dataset, 7, bit)
        except KeyError:
            import h5py
            with h5py.File(cp, "r") as f:
                names = []
                f.visit(names.append)
            check(f"dataset {dataset} exists ({', '.join(names)[:300]})", False)
            continue
        p = burst(args, out, ["-max_steps", "12", "-restart", cp])
        check(f"a flipped {name} bit in {dataset}: refused naming the file and the checksum", refused(p, r"Checkpoint .*checkpoint_000010\.h5: it fails its checksum \(stored [0-9a-f]{16}, computed [0-9a-f]{16}\)"), p.text)
    p = burst(args, out, ["-max_steps", "12", "-restart", out])
    check("-restart on the folder skips it with a note", re.search(r"Note: -restart .*: skipping checkpoint_000010\.h5: it fails its checksum", p.text) is not None, p.text)
    check("and continues from the older valid checkpoint_000005.h5", p.returncode == 0 and re.search(r"Restarted from .*checkpoint_000005\.h5", p.text) is not None, p.text)
    check.finish()


def options(args):
    check = Check("reliability_options")
    out = fresh(os.path.join(args.out, "folder"))
    burst(args, out, ["-max_steps", "5", "-checkpoint_interval", "5"])
    cp = os.path.join(out, "checkpoint_000005.h5")
    p = burst(args, out, ["-max_steps", "6", "-restart", cp, "-steel_density", "7900"])
    check("a changed material option is refused naming it and both values", refused(p, r"Checkpoint .*checkpoint_000005\.h5 was written with other physics options than this run's \(1 differ\): -steel_density is '7830' in the checkpoint, '7900' in this run.*-restart_allow_option_change"), p.text)
    p = burst(args, out, ["-max_steps", "6", "-restart", cp, "-ring_radial_velocity", "310", "-mpm_cfl", "0.3"])
    check("two changed options (geometry, numerics) are both named", refused(p, r"\(2 differ\): -mpm_cfl is '0\.4' in the checkpoint, '0\.3' in this run; -ring_radial_velocity is '300' in the checkpoint, '310' in this run"), p.text)
    p = burst(args, out, ["-max_steps", "6", "-restart", cp, "-steel_density", "7900", "-restart_allow_option_change"])
    check("-restart_allow_option_change continues with a note", p.returncode == 0 and "Note: restart with a changed physics option (-restart_allow_option_change): -steel_density is '7830' in the checkpoint, '7900' in this run" in p.text, p.text)
    p = burst(args, out, ["-max_steps", "7", "-restart", cp, "-output_interval", "1", "-monitor_interval", "1", "-steel_density", "7830.0"])
    check("output options and an equal number written otherwise may change", p.returncode == 0 and "Restarted from" in p.text, p.text)
    check.finish()


def legacy(args):
    import h5py
    check = Check("reliability_legacy")
    out = fresh(os.path.join(args.out, "folder"))
    burst(args, out, ["-max_steps", "5", "-checkpoint_interval", "5"])
    cp = os.path.join(out, "checkpoint_000005.h5")
    with h5py.File(cp, "r+") as f:
        for a in ("format", "run_id", "physics_hash", "physics_options", "written_at", "checksum"):
            if a in f.attrs:
                del f.attrs[a]
    p = burst(args, out, ["-max_steps", "6", "-restart", cp])
    check("a checkpoint without identity is accepted with a note", p.returncode == 0 and re.search(r"Note: checkpoint .*checkpoint_000005\.h5 carries no run id, physics options or checksum .*: it is not verified, and this run continues as run [0-9a-f]{16}", p.text) is not None, p.text)
    # a checkpoint whose parts another version wrote (format 2 kept every number in /run): refused,
    # naming the part and both lists of values
    out = fresh(os.path.join(args.out, "parts"))
    burst(args, out, ["-max_steps", "5", "-checkpoint_interval", "5"])
    cp = os.path.join(out, "checkpoint_000005.h5")
    with h5py.File(cp, "r+") as f:
        del f.attrs["fragments_values"]
    p = burst(args, out, ["-max_steps", "6", "-restart", cp])
    check("a checkpoint without a part's values is refused, naming it", refused(p, r"does not hold this burst's run-wide values for /fragments \(it holds 'none', this burst keeps 'fracture_velocity:1,fracture_time:1,"), p.text)
    check.finish()




def dead_pid():
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def write_lock(out, host, pid, age=0):
    path = os.path.join(out, ".burst.lock")
    with open(path, "w") as f:
        f.write(f"host {host}\npid {pid}\nstarted 2026-01-01 00:00:00 UTC\n")
    if age:
        t = time.time() - age
        os.utime(path, (t, t))
    return path


def lock(args):
    check = Check(f"reliability_lock_{args.case}")
    out = fresh(os.path.join(args.out, args.case))
    lock_file = os.path.join(out, ".burst.lock")
    host = socket.gethostname()
    if args.case == "live":
        first = burst(args, out, ["-max_steps", "100000000", "-final_time", "1e30", "-mpm_dt", "1e-9", "-monitor_interval", "1"], wait=False)
        running = wait_for(os.path.join(out, "monitor.csv"), "\n3,", first)
        check("the first run is stepping", running)
        for ranks in (1, 2):
            p = burst(args, out, ["-max_steps", "2"], ranks=ranks)
            check(f"a second run on {ranks} rank(s) is refused naming the holder's host and pid", refused(p, rf"Option -output_dir .*: it is in use by another run: host {re.escape(host)}, pid {first.pid}, started .*\(lock file .*\.burst\.lock\)"), p.text)
        first.send_signal(signal.SIGTERM)  # a checkpoint and a clean stop
        text = first.communicate(timeout=300)[0]
        check("the first run ends normally (exit 0) after the refusals", first.returncode == 0 and "Stopping at step" in text, text)
        check("and removes its lock", not os.path.exists(lock_file))
    elif args.case == "stale":
        pid = dead_pid()
        write_lock(out, host, pid)
        p = burst(args, out, ["-max_steps", "2"])
        check("a dead pid's lock on this host is taken over with a note", p.returncode == 0 and f"Note: taking over the stale lock {lock_file} of host {host}, pid {pid}: process {pid} no longer runs burst on this host" in p.text, p.text)
        check("the lock is gone after the run", not os.path.exists(lock_file))
        with open(write_lock(out, host, os.getpid()), "a") as f:  # a live pid that runs another program
            f.write("program burst\n")
        p = burst(args, out, ["-max_steps", "2"])
        check("a lock whose pid now runs another program is taken over with a note", p.returncode == 0 and f"pid {os.getpid()}: process {os.getpid()} no longer runs burst on this host" in p.text, p.text)
        write_lock(out, "another-host.example", 4242, age=7200)
        p = burst(args, out, ["-max_steps", "2"])
        check("another host's lock untouched for 2 h is taken over with a note", p.returncode == 0 and "Note: taking over the stale lock" in p.text and "host another-host.example has not touched it for" in p.text, p.text)
        write_lock(out, "another-host.example", 4242, age=120)
        p = burst(args, out, ["-max_steps", "2", "-output_lock_stale_time", "60"])
        check("with -output_lock_stale_time 60 a 2-minute-old lock is stale", p.returncode == 0 and "(-output_lock_stale_time 60)" in p.text, p.text)
        p = burst(args, out, ["-max_steps", "2", "-restart", os.path.join(out, "nothing.h5")])
        check("a run that stops with an error removes its lock", p.returncode != 0 and not os.path.exists(lock_file), p.text)
    elif args.case == "fresh":
        write_lock(out, "another-host.example", 4242, age=10)
        p = burst(args, out, ["-max_steps", "2"])
        check("another host's recent lock is refused naming host and pid", refused(p, r"it is in use by another run: host another-host\.example, pid 4242"), p.text)
        check("the refused run wrote nothing", sorted(os.listdir(out)) == [".burst.lock"])
    elif args.case == "concurrent":
        extra = ["-max_steps", "100", "-monitor_interval", "10"]
        a, b = burst(args, out, extra, wait=False), burst(args, out, extra, wait=False)
        ta, tb = a.communicate(timeout=300)[0], b.communicate(timeout=300)[0]
        ok = sorted([a.returncode == 0, b.returncode == 0]) == [False, True]
        check("of two runs started at once exactly one runs", ok, ta + tb)
        if ok:
            (win, wtext), (lose, ltext) = ((a, ta), (b, tb)) if a.returncode == 0 else ((b, tb), (a, ta))
            check("the other is refused naming the winner's pid", re.search(rf"in use by another run: host {re.escape(host)}, pid {win.pid}", ltext) is not None, ltext)
            rows = [l for l in open(os.path.join(out, "monitor.csv")) if l[:1].isdigit()]
            check("monitor.csv holds one run's rows (0, 10, ..., 100 once each)", [int(l.split(",")[0]) for l in rows] == list(range(0, 101, 10)))
            check("the lock is gone", not os.path.exists(lock_file))
    check.finish()


def optionfile(args):
    check = Check(f"reliability_optionfile_{args.case}")
    out = fresh(os.path.join(args.out, args.case))
    ring = os.path.join(ROOT, RING)

    def write(name, text):
        path = os.path.join(out, name)
        with open(path, "wb") as f:
            f.write(text.encode() if isinstance(text, str) else text)
        return path

    if args.case == "self":
        top = write("self.opts", f"-options_file {ring}\n-max_steps 1\n-options_file {os.path.join(out, 'self.opts')}\n")
        pattern = r"Option file .*self\.opts includes itself: chain of option files .*self\.opts -> .*self\.opts \(-options_file on line 3 of .*self\.opts\)"
    elif args.case == "pair":
        write("b.opts", f"-max_steps 1\n-options_file {os.path.join(out, 'a.opts')}\n")
        top = write("a.opts", f"-options_file {ring}\n-options_file {os.path.join(out, 'b.opts')}\n")
        pattern = r"Option files include each other in a loop: chain of option files .*a\.opts -> .*b\.opts -> .*a\.opts \(-options_file on line 2 of .*b\.opts\)"
    elif args.case == "deep":
        for k in range(20):
            write(f"level{k}.opts", f"-options_file {os.path.join(out, f'level{k + 1}.opts')}\n" if k < 19 else f"-options_file {ring}\n")
        top = os.path.join(out, "level0.opts")
        pattern = r"Option files nested deeper than 16 levels: chain of option files .*level0\.opts -> .*level1\.opts -> .*level16\.opts"
    elif args.case == "nul":
        top = write("nul.opts", b"-options_file " + ring.encode() + b"\n-max_steps 1\n-mpm_cfl 0.3\x00 -mpm_shape_type linear\n")
        pattern = r"Option file .*nul\.opts, line 3, column 13: a NUL byte"
    else:  # dangling
        top = write("dangling.opts", f"-options_file {ring}\n-max_steps 1\n-options_file\n")
        pattern = r"Option file .*dangling\.opts, line 3: -options_file names no file \(it is the last option of the file\)"
    p = subprocess.run([args.burst, "-options_file", top, "-output_dir", os.path.join(out, "run"), "-max_steps", "1"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    text = p.stdout + p.stderr
    check(f"exit {p.returncode}, no crash, the message names the file(s) and line", p.returncode > 0 and re.search(pattern, text) is not None and "Caught signal" not in text, text or "(no output)")
    check.finish()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("check", choices=["foreign", "lineage", "corrupt", "options", "legacy", "lock", "optionfile"])
    p.add_argument("--burst", required=True)
    p.add_argument("--out", default="reliability_tests")
    p.add_argument("--case", default="")
    args = p.parse_args()
    args.out = os.path.join(os.path.abspath(args.out), args.check + (f"_{args.case}" if args.case else ""))  # tests apart under ctest -j
    os.makedirs(args.out, exist_ok=True)
    {"foreign": foreign, "lineage": lineage, "corrupt": corrupt, "options": options, "legacy": legacy, "lock": lock, "optionfile": optionfile}[args.check](args)


if __name__ == "__main__":
    main()
