#!/usr/bin/python3
"""A full disk: a run writing its output into a 64 kB tmpfs must stop naming the folder, the partial
files it removed and "the disk is full", and leave no *.tmp file behind. Needs root to mount the
tmpfs; where mounting is not allowed the test is skipped (exit 77, ctest's SKIP_RETURN_CODE).
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    args = p.parse_args()
    mnt = tempfile.mkdtemp(prefix="burst_full_")
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt], capture_output=True).returncode != 0:
        print("SKIP: cannot mount a tmpfs here (needs root)")
        os.rmdir(mnt)
        sys.exit(77)
    try:
        out = os.path.join(mnt, "run")
        proc = subprocess.run([args.burst, "-options_file", "options/scenes/colliding_disks.opts", "-output_dir", out, "-output_interval", "1",
                               "-max_steps", "50", "-progress", "false"], cwd=ROOT, capture_output=True, text=True)
        text = proc.stdout + proc.stderr
        lines = [line for line in text.splitlines() if line.startswith("burst: writing")]
        left = glob.glob(os.path.join(out, "*.tmp"))
        print(f"exit code {proc.returncode}; {lines[0] if lines else 'no message from burst'}; *.tmp left: {left}")
        failures = []
        if proc.returncode == 0:
            failures.append("the run did not stop")
        if not lines or "the disk is full" not in lines[0] or out not in lines[0] or "partial files removed" not in lines[0]:
            failures.append("the message does not name the folder, the partial files and the full disk")
        if left:
            failures.append("partial files left")
    finally:
        subprocess.run(["umount", mnt])
        os.rmdir(mnt)
    print(f"disk_full: {'FAIL (' + '; '.join(failures) + ')' if failures else 'OK'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
