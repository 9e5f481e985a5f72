#!/usr/bin/python3
"""One Grady velocity for every regularisation: the expansion velocity when a failure criterion is
first met. The crack band starts softening where the run without a length fails a particle, and the
two runs are the same step for step until then, so cylinder2d_hy100 at --cells with the crack band
(as shipped) and with -hy100_regularization none must record the same first-failure time and
velocity (summary.json fracture_time, fracture_velocity) to round-off, and both a Grady band.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from verify import check, finish  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--cells", type=int, default=80)
    args = p.parse_args()
    failures, runs = [], {}
    for name, extra in (("crack band", []), ("no length", ["-hy100_regularization", "none"])):
        with tempfile.TemporaryDirectory() as out:
            cmd = [args.burst, "-options_file", "options/scenes/cylinder2d_hy100.opts", "-grid_cells", f"{args.cells},{args.cells}", "-output_dir", out,
                   "-progress", "false", "-output_interval", "0", *extra]
            proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
            if proc.returncode:
                sys.stdout.write(proc.stdout[-3000:] + proc.stderr[-3000:])
                raise SystemExit(f"FAIL: burst exited with {proc.returncode}")
            with open(os.path.join(out, "summary.json")) as f:
                runs[name] = json.load(f)
        s = runs[name]
        print(f"cylinder2d_hy100, {args.cells} cells, {name}: first criterion at {s['fracture_time']:.6g} s, V = {s['fracture_velocity']:.6f} m/s; "
              f"{s['fragment_count']} fragments, Grady {s['grady_shear'] and s['grady_shear']['sector']}")
        if not s["grady_shear"]:
            failures.append(f"{name}: no Grady band")
    a, b = runs["crack band"], runs["no length"]
    check("|V(crack band) - V(no length)| / V(no length)", abs(a["fracture_velocity"] - b["fracture_velocity"]) / abs(b["fracture_velocity"]), 1e-12, failures)
    check("|t(crack band) - t(no length)| / t(no length)", abs(a["fracture_time"] - b["fracture_time"]) / abs(b["fracture_time"]), 1e-12, failures)
    finish("grady_onset", failures)


if __name__ == "__main__":
    main()
