#!/usr/bin/python3
"""Fuzzed input (issue 11): mutate the shipped option files and check that burst either runs or stops
with a message naming an option; never a crash, a hang, or a NaN taken silently.

Each case takes one shipped option file (options/scenes, tests/decks, tutorials; its -options_file
includes are expanded so material parameters are mutated too) and applies one mutation:
  drop        remove one option
  negative    a numeric value made negative        zero     a numeric value set to 0
  huge        a numeric value set to 1e300         nan      a numeric value set to nan
  text        a numeric value set to 'abc'         misspell an option name with one letter changed
  components  a comma list with one value more or one less
then runs burst for at most 2 steps. Verdicts:
  OK  exit 0 (a value or a drop that is acceptable), or an error whose message names an option;
  FAIL a signal or crash, a timeout (hang), an error message that names no option, or exit 0 after a
       nan or 'abc' was given for a number (taken silently).
The seed is printed; rerun one case with --seed S --cases N --only K.

  python3 tests/fuzz_options.py --burst build/burst --cases 400            # the long form
  python3 tests/fuzz_options.py --burst build/burst --cases 40 --seed 1    # the short form (ctest)
"""
import argparse
import glob
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OPTION = re.compile(r"^-[A-Za-z][A-Za-z0-9_]*$")
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
MUTATIONS = ["drop", "negative", "zero", "huge", "nan", "text", "misspell", "components"]
# the message of a PETSc error: the lines between "Error Message" and "See https" (not the option table)
NAMES_OPTION = re.compile(r"-[a-z][a-z0-9_]*[a-z0-9]", re.I)


def parse(path, seen=None):
    """The options of a file as [name, value] pairs, includes expanded in place."""
    seen = seen or set()
    out = []
    full = path if os.path.isabs(path) else os.path.join(ROOT, path)
    if full in seen:
        return out
    seen.add(full)
    for line in open(full):
        tokens = line.split("#", 1)[0].split()
        i = 0
        while i < len(tokens):
            if OPTION.match(tokens[i]):
                name, value = tokens[i], []
                i += 1
                while i < len(tokens) and not OPTION.match(tokens[i]):
                    value.append(tokens[i])
                    i += 1
                if name == "-options_file" and value:
                    out.extend(parse(value[0], seen))
                else:
                    out.append([name, " ".join(value)])
            else:
                i += 1
    return out


def numeric(value):
    parts = value.split(",")
    return value and all(NUMBER.match(p) for p in parts)


def mutate(options, rng):
    """One mutation; returns (options, description, kind, name) or None if it does not apply."""
    kind = rng.choice(MUTATIONS)
    opts = [list(o) for o in options]
    candidates = list(range(len(opts)))
    if kind in ("negative", "zero", "huge", "nan", "text"):
        candidates = [i for i in candidates if numeric(opts[i][1])]
    elif kind == "components":
        candidates = [i for i in candidates if numeric(opts[i][1]) and "," in opts[i][1]]
    if not candidates:
        return None
    i = rng.choice(candidates)
    name, value = opts[i]
    if kind == "drop":
        del opts[i]
        return opts, f"drop {name} {value}", kind, name
    if kind == "misspell":
        body = name[1:]
        k = rng.randrange(len(body))
        letter = rng.choice("abcdefghijklmnopqrstuvwxyz")
        if letter == body[k]:
            letter = "q" if body[k] != "q" else "z"
        opts[i][0] = "-" + body[:k] + letter + body[k + 1:]
        return opts, f"misspell {name} -> {opts[i][0]}", kind, opts[i][0]
    parts = value.split(",")
    k = rng.randrange(len(parts))
    if kind == "components":
        parts = parts[:-1] if rng.random() < 0.5 else parts + [parts[-1]]
    else:
        parts[k] = {"negative": "-" + parts[k].lstrip("+-") if not parts[k].startswith("-") else parts[k][1:] + "0", "zero": "0", "huge": "1e300", "nan": "nan", "text": "abc"}[kind]
    opts[i][1] = ",".join(parts)
    return opts, f"{kind} {name} {value} -> {opts[i][1]}", kind, name


def error_message(text):
    lines, inside = [], False
    for line in text.splitlines():
        if "PETSC ERROR" not in line:
            continue
        if "Error Message" in line:
            inside = True
            continue
        if "See https://petsc.org" in line or "Option left" in line:
            inside = False
        if inside:
            lines.append(line.split("PETSC ERROR:", 1)[1])
    return "\n".join(lines)


def run_case(args, index, deck, opts, description, kind, work):
    path = os.path.join(work, f"case{index}.opts")
    with open(path, "w") as f:
        for name, value in opts:
            f.write(f"{name} {value}\n")
    out = os.path.join(work, f"out{index}")
    cmd = [args.burst, "-options_file", path, "-output_dir", out, "-max_steps", "2", "-progress", "false", "-no_signal_handler"]
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return False, f"hang (no exit within {args.timeout} s)"
    finally:
        shutil.rmtree(out, ignore_errors=True)
    text = proc.stdout + proc.stderr
    if proc.returncode == 0:
        if kind in ("nan", "text"):
            return False, "ran to the end with a nan or non-numeric number (taken silently)"
        return True, "ran"
    if proc.returncode < 0 or "Caught signal" in text or "Segmentation" in text or "AddressSanitizer" in text:
        return False, f"crashed (exit {proc.returncode})"
    message = error_message(text)
    if not message:
        return False, f"exit {proc.returncode} without a PETSc error message: {text.strip()[-300:]}"
    if not NAMES_OPTION.search(message):
        return False, "error message names no option: " + " ".join(message.split())[:300]
    return True, "stopped: " + " ".join(message.split())[:160]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--cases", type=int, default=400)
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--only", type=int, default=None, help="run only this case number (replay)")
    p.add_argument("--timeout", type=float, default=120)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--verbose", action="store_true")
    args = p.parse_args()
    seed = args.seed if args.seed is not None else random.randrange(1 << 30)
    print(f"fuzz_options: seed {seed}, {args.cases} cases (replay: --seed {seed} --cases {args.cases} --only K)")
    rng = random.Random(seed)
    decks = sorted(glob.glob(os.path.join(ROOT, "options/scenes/*.opts")) + glob.glob(os.path.join(ROOT, "tests/decks/*.opts")) + glob.glob(os.path.join(ROOT, "tutorials/*.opts")))
    # a later value of an option replaces an earlier one (as in PETSc): keep the last of each
    # a later value of an option replaces an earlier one (as in PETSc): keep the last of each; the
    # options this script sets itself are not mutated
    own = {"-max_steps", "-output_dir", "-progress"}
    parsed = {d: [o for k, o in enumerate(parse(d)) if o[0] not in own and o[0] not in [q[0] for q in parse(d)[k + 1:]]] for d in decks}
    cases = []
    while len(cases) < args.cases:
        deck = rng.choice(decks)
        m = mutate(parsed[deck], rng)
        if m:
            cases.append((len(cases), deck, *m))
    if args.only is not None:
        cases = [cases[args.only]]
    work = tempfile.mkdtemp(prefix="burst_fuzz_")
    failures = []

    def one(case):
        index, deck, opts, description, kind, name = case
        ok, what = run_case(args, index, deck, opts, description, kind, work)
        line = f"  case {index}: {os.path.relpath(deck, ROOT)}: {description}: {'OK' if ok else 'FAIL'} ({what})"
        return ok, line

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for ok, line in pool.map(one, cases):
            if not ok:
                failures.append(line)
            if args.verbose or not ok:
                print(line, flush=True)
    shutil.rmtree(work, ignore_errors=True)
    print(f"fuzz_options: {len(cases) - len(failures)} of {len(cases)} cases ran or stopped naming an option (seed {seed})")
    if failures:
        print(f"fuzz_options: FAIL ({len(failures)} cases)")
        sys.exit(1)
    print("fuzz_options: OK")


if __name__ == "__main__":
    main()
