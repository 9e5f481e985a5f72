#!/usr/bin/python3
"""Strong and weak scaling of burst's scenes; writes CSV and PNG, never fails on time.

  strong: the same problem on each rank count of --ranks: speed-up T(1)/T(n) and parallel
          efficiency T(1)/(n T(n)) of the stepping wall time (summary.json, without set-up and
          output), the best of --repeats runs.
  weak:   the problem grows with the ranks (the cells refined so that the particles per rank stay
          about the same): efficiency T(1)/T(n) (particle-steps per second per core ratio).
  balance: (--kinds balance) the strong problem on the largest of --ranks without and with
          -grid_balance: stepping time, speed-up over one rank, and the imbalance of the particle work
          (the max/min ratio over ranks of the G2P time, a phase without communication, -log_view).
  check:  the strong problem on each of --check-ranks (oversubscribed on a small machine) against one
          rank: the largest relative difference of the final kinetic and internal energies, momentum
          and mass (the answers must stay the same to round-off; the times are not used).
Scenes (--scenes): cylinder (options/scenes/cylinder2d_4340.opts, the prescribed-pressure 4340
cylinder, 2-D), taylor (tests/decks/taylor3d.opts, 3-D Taylor impact, copper on a rigid anvil),
exploding (options/scenes/exploding_cylinder2d.opts, gas and solid; -grid_balance at start-up only).
The launcher is a template: --launcher "srun -n {n}" or "mpiexec -n {n} --bind-to core" on a cluster;
one rank runs without it unless --launch-one. --balance adds -grid_balance (DMDA ownership ranges from
the particle work, grid.cxx); --extra passes further options to every run.
Outputs (--out, default build/scaling): scaling.csv (one row per scene, kind and rank count),
checks.csv, scaling.png (speed-up and efficiency against ranks, strong and weak).
Example: scripts/study_scaling.py --burst build/burst --ranks 1,2 --check-ranks 4"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import cpu_name  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_LAUNCHER = "mpiexec --allow-run-as-root --oversubscribe -x OMP_NUM_THREADS=1 -n {n}"

# name: (base options, steps, weak-scaling options for n ranks)
SCENES = {
    "cylinder": (["-options_file", "options/scenes/cylinder2d_4340.opts", "-wall_seeding", "lattice", "-grid_upper", "0.12,0.12", "-output_interval", "0", "-output_grid", "false", "-fragments", "false",
                  "-progress", "false", "-monitor_interval", "100000", "-final_time", "1.2e-4"], 300,
                 lambda n: ["-grid_cells", f"{round(160 * math.sqrt(n))},{round(160 * math.sqrt(n))}"]),
    "taylor": (["-options_file", "tests/decks/taylor3d.opts"], 150,
               lambda n: ["-grid_cell_size", ",".join([f"{0.0005 / n ** (1 / 3):.6g}"] * 3)]),
    "exploding": (["-options_file", "options/scenes/exploding_cylinder2d.opts", "-output_interval", "0", "-output_grid", "false", "-progress", "false",
                   "-monitor_interval", "100000"], 100,
                  lambda n: []),
}


def run(args, n, options, log=False):
    """One run on n ranks; returns summary.json as a dict (with -log_view: its G2P max/min time ratio
    over ranks as "g2p_imbalance")."""
    if log:
        options = [*options, "-log_view"]
    with tempfile.TemporaryDirectory() as out:
        launch = shlex.split(args.launcher.format(n=n)) if (n > 1 or args.launch_one) else []
        cmd = launch + [args.burst, *options, "-output_dir", out, *shlex.split(args.extra)]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            print(proc.stdout[-3000:], proc.stderr[-3000:])
            raise SystemExit(f"run failed: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        if log:
            line = next(line for line in proc.stdout.splitlines() if line.startswith("MPM_G2P"))
            summary["g2p_imbalance"] = float(line.split()[4])
        return summary


def best_of(args, n, options, log=False):
    runs = [run(args, n, options, log) for _ in range(args.repeats)]
    return min(runs, key=lambda s: s["wall_time_s"])


def relative_difference(a, b):
    diffs = []
    for key in ("kinetic_energy", "internal_energy", "mass"):
        diffs.append(abs(a[key] - b[key]) / max(abs(a[key]), abs(b[key]), 1e-300))
    scale = max(math.sqrt(sum(x * x for x in a["momentum"])), 1e-300)
    diffs.append(math.sqrt(sum((x - y) ** 2 for x, y in zip(a["momentum"], b["momentum"]))) / scale)
    return max(diffs)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--scenes", default="cylinder,taylor", help="comma-separated: " + ",".join(SCENES))
    p.add_argument("--ranks", default="1,2", help="rank counts timed (default 1,2)")
    p.add_argument("--check-ranks", default="4", help="rank counts whose answers are compared with one rank (default 4; '' for none)")
    p.add_argument("--kinds", default="strong,weak", help="any of strong, weak, balance")
    p.add_argument("--launcher", default=DEFAULT_LAUNCHER, help="launch command template with {n} (default: %(default)s)")
    p.add_argument("--launch-one", action="store_true", help="use the launcher for one rank too")
    p.add_argument("--repeats", type=int, default=2, help="runs per point; the fastest is kept (default 2)")
    p.add_argument("--steps", type=int, default=0, help="steps per run (default: the scene's)")
    p.add_argument("--balance", action="store_true", help="add -grid_balance (ownership ranges from the particle work)")
    p.add_argument("--extra", default="", help="further options for every run")
    p.add_argument("--out", default=os.path.join(ROOT, "build", "scaling"))
    args = p.parse_args()
    args.burst = os.path.abspath(args.burst)
    if args.balance:
        args.extra += " -grid_balance"
    os.makedirs(args.out, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    checks = [int(r) for r in args.check_ranks.split(",") if r]
    machine = f"{cpu_name()}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, {datetime.date.today()}"
    print(f"burst scaling study on {machine}; launcher: {args.launcher}; extra: {args.extra.strip() or '-'}")
    rows, check_rows, all_balance = [], [], []
    for scene in args.scenes.split(","):
        base, steps, weak = SCENES[scene]
        steps = args.steps or steps
        options = [*base, "-max_steps", str(steps)]
        balance_rows = []
        for kind in args.kinds.split(","):
            if kind == "balance":
                one = best_of(args, 1, options)
                n = max(ranks)
                for balanced in (False, True):
                    s = best_of(args, n, options + (["-grid_balance"] if balanced else []), log=True)
                    row = dict(scene=scene, ranks=n, balance=balanced, particles=s["particles"], steps=s["steps"], wall_s=s["wall_time_s"],
                               speedup=one["wall_time_s"] / s["wall_time_s"], efficiency=one["wall_time_s"] / (n * s["wall_time_s"]),
                               g2p_imbalance=s["g2p_imbalance"])
                    balance_rows.append(row)
                    print(f"{scene:>10} {n} ranks, -grid_balance {'on ' if balanced else 'off'}: stepping {row['wall_s']:.3f} s (1 rank {one['wall_time_s']:.3f} s), "
                          f"speed-up {row['speedup']:.2f}, efficiency {100 * row['efficiency']:.0f} %, G2P time max/min over ranks {row['g2p_imbalance']:.2f}", flush=True)
                all_balance.extend(balance_rows)
                continue
            t1 = None
            for n in ranks:
                s = best_of(args, n, options + (weak(n) if kind == "weak" else []))
                t = s["wall_time_s"]
                rate = s["particle_steps_per_second_per_core"]
                if t1 is None:
                    t1, rate1, n1 = t, rate, n
                speedup = t1 / t * (1 if kind == "strong" else n / n1)
                efficiency = (t1 * n1 / (n * t)) if kind == "strong" else rate / rate1
                rows.append(dict(scene=scene, kind=kind, ranks=n, particles=s["particles"], steps=s["steps"], wall_s=t,
                                 particle_steps_per_s_per_core=rate, speedup=speedup, efficiency=efficiency))
                print(f"{scene:>10} {kind:>6} {n:>3} ranks: {s['particles']:>8} particles, {s['steps']} steps, stepping {t:.3f} s, "
                      f"{rate / 1e3:.1f} k particle-steps/s/core, speed-up {speedup:.2f}, efficiency {100 * efficiency:.0f} %", flush=True)
        if checks:
            reference = run(args, 1, options)
            for n in checks:
                s = run(args, n, options)
                d = relative_difference(reference, s)
                check_rows.append(dict(scene=scene, ranks=n, particles=s["particles"], max_relative_difference=d))
                print(f"{scene:>10} check {n} ranks against 1: largest relative difference of energies, momentum, mass {d:.2e}"
                      f" ({'same to round-off' if d < 1e-9 else 'DIFFERENT'})", flush=True)
    if all_balance:
        with open(os.path.join(args.out, "balance.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(all_balance[0].keys()))
            w.writeheader()
            w.writerows(all_balance)
    if not rows:
        return
    with open(os.path.join(args.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    if check_rows:
        with open(os.path.join(args.out, "checks.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(check_rows[0].keys()))
            w.writeheader()
            w.writerows(check_rows)
    plot(rows, machine, os.path.join(args.out, "scaling.png"))
    print(f"wrote {args.out}/scaling.csv, scaling.png" + (", checks.csv" if check_rows else ""))


def plot(rows, machine, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for scene in sorted({r["scene"] for r in rows}):
        for kind, style in (("strong", "o-"), ("weak", "s--")):
            sel = [r for r in rows if r["scene"] == scene and r["kind"] == kind]
            if not sel:
                continue
            n = [r["ranks"] for r in sel]
            axes[0].plot(n, [r["speedup"] for r in sel], style, label=f"{scene}, {kind}")
            axes[1].plot(n, [100 * r["efficiency"] for r in sel], style, label=f"{scene}, {kind}")
    n_all = sorted({r["ranks"] for r in rows})
    axes[0].plot(n_all, n_all, "k:", label="ideal")
    axes[0].set_xlabel("ranks")
    axes[0].set_ylabel("speed-up")
    axes[1].axhline(100, color="k", linestyle=":")
    axes[1].set_xlabel("ranks")
    axes[1].set_ylabel("parallel efficiency (%)")
    axes[1].set_ylim(0, 110)
    for ax in axes:
        ax.set_xticks(n_all)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"burst scaling (stepping wall time; weak: particle-steps/s/core)\n{machine}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
