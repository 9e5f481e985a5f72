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
then runs burst for at most 2 steps (class values). Further classes (--classes):
  files        the case's option file includes itself, or a partner file that includes it back, or
               starts a chain of 17 to 24 files; a NUL byte at a random place; an -options_file with no
               file (at the end of the file or before another option): refused, naming the file
  checkpoints  2 steps with a checkpoint each step, then: a random bit of a random entry of a random
               dataset flipped (-restart refused by the checksum, naming the file); another run into
               the same folder (the first run's checkpoints kept byte for byte in other_runs/<run id>/,
               -restart on the folder continues the second); a restart with a physics option changed
               (refused naming it)
  concurrent   two runs started at once into one folder: one runs, the other is refused naming the
               lock's holder (or, when the first is already done, runs too); never a crash or a
               failed rename
Verdicts (class values):
  OK  exit 0 (a value or a drop that is acceptable), or an error whose message names an option;
  FAIL a signal or crash, a timeout (hang), an error message that names no option, or exit 0 after a
       nan or 'abc' was given for a number (taken silently).
The seed is printed; rerun one case with --seed S --cases N --only K.

  python3 tests/fuzz_options.py --burst build/burst --cases 400            # the long form
  python3 tests/fuzz_options.py --burst build/burst --cases 40 --seed 1    # the short form (ctest)
  python3 tests/fuzz_options.py --burst build/burst --classes files,checkpoints,concurrent --cases 12
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
CLASSES = {"values": MUTATIONS, "files": ["include_self", "include_pair", "include_deep", "nul", "dangling"],
           "checkpoints": ["corrupt_bit", "foreign_folder", "option_change"], "concurrent": ["concurrent"]}
RUN_CONTROL = re.compile(r"^-(output_|checkpoint_|monitor_|restart|log|options_|progress|fragments|grady|grid_balance|max_steps|final_time|max_wall_time|stop_kinetic_fraction|mpm_energy_growth_limit|scene|mode)")
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


def crashed(proc, text):
    return proc.returncode < 0 or "Caught signal" in text or "Segmentation" in text or "AddressSanitizer" in text


def write_options(path, opts):
    with open(path, "w") as f:
        for name, value in opts:
            f.write(f"{name} {value}\n")


def file_case(args, index, opts, kind, rng, work):
    """An option file the pre-scan must refuse; returns (ok, what)."""
    base = os.path.join(work, f"case{index}")
    os.makedirs(base, exist_ok=True)
    path = os.path.join(base, "case.opts")
    lines = [f"{n} {v}" for n, v in opts]
    at = rng.randrange(len(lines) + 1)
    if kind == "include_self":
        lines.insert(at, f"-options_file {path}")
        expect = r"includes itself: chain of option files"
    elif kind == "include_pair":
        partner = os.path.join(base, "partner.opts")
        with open(partner, "w") as f:
            f.write(f"-options_file {path}\n")
        lines.insert(at, f"-options_file {partner}")
        expect = r"include each other in a loop: chain of option files .*case\.opts -> .*partner\.opts -> .*case\.opts"
    elif kind == "include_deep":
        depth = rng.randrange(17, 25)
        for k in range(depth):
            with open(os.path.join(base, f"level{k}.opts"), "w") as f:
                f.write(f"-options_file {os.path.join(base, f'level{k + 1}.opts')}\n" if k + 1 < depth else "-max_steps 1\n")
        lines.insert(at, f"-options_file {os.path.join(base, 'level0.opts')}")
        expect = r"nested deeper than 16 levels"
    elif kind == "dangling":
        at = len(lines) if rng.random() < 0.5 else at
        lines.insert(at, "-options_file")
        expect = rf"case\.opts, line {at + 1}: -options_file names no file"
    text = "\n".join(lines) + "\n"
    if kind == "nul":
        k = rng.randrange(len(text))
        text = text[:k] + "\0" + text[k:]
        line = text[:k].count("\n") + 1
        expect = rf"case\.opts, line {line}, column [0-9]+: a NUL byte"
    with open(path, "w") as f:
        f.write(text)
    cmd = [args.burst, "-options_file", path, "-output_dir", os.path.join(base, "out"), "-max_steps", "2", "-progress", "false", "-no_signal_handler"]
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=args.timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return False, f"hang (no exit within {args.timeout} s)"
    out = proc.stdout + proc.stderr
    if crashed(proc, out):
        return False, f"crashed (exit {proc.returncode})"
    if proc.returncode == 0:
        return False, "ran: the option file was not refused"
    if not re.search(expect, out):
        return False, f"refused without naming the file/line ({expect}): " + " ".join(error_message(out).split())[:300]
    return True, "refused: " + " ".join(error_message(out).split())[:160]


def run(args, cmd, timeout=None):
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout or args.timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return None, ""
    return proc, proc.stdout + proc.stderr


def checkpoint_case(args, index, opts, kind, rng, work):
    import h5py
    import numpy as np
    base = os.path.join(work, f"case{index}")
    os.makedirs(base, exist_ok=True)
    deck = os.path.join(base, "case.opts")
    write_options(deck, opts)
    out = os.path.join(base, "out")
    common = ["-output_dir", out, "-progress", "false", "-no_signal_handler", "-output_interval", "0"]
    proc, text = run(args, [args.burst, "-options_file", deck, *common, "-max_steps", "2", "-checkpoint_interval", "1", "-checkpoint_keep", "5"])
    if proc is None:
        return False, "hang in the first run"
    if crashed(proc, text):
        return False, f"first run crashed (exit {proc.returncode})"
    cps = sorted(n for n in os.listdir(out) if re.fullmatch(r"checkpoint_\d+\.h5", n)) if os.path.isdir(out) else []
    if proc.returncode != 0 or not cps:
        return True, "deck does not run 2 steps here (skipped)"
    cp = os.path.join(out, cps[-1])
    if kind == "corrupt_bit":
        with h5py.File(cp, "r+") as f:
            names = []
            f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) and o.size else None)
            name = rng.choice(names)
            d = f[name]
            flat = d[()].astype(np.float64).reshape(-1)
            k, bit = rng.randrange(flat.size), rng.randrange(64)
            flat.view(np.uint64)[k] ^= np.uint64(1) << np.uint64(bit)
            d[...] = flat.reshape(d.shape)
        proc, text = run(args, [args.burst, "-options_file", deck, *common, "-max_steps", "3", "-restart", cp])
        expect, what = rf"{re.escape(cps[-1])}: it fails its checksum", f"bit {bit} of entry {k} of {name}"
    elif kind == "foreign_folder":
        before = {c: open(os.path.join(out, c), "rb").read() for c in cps}
        proc, text = run(args, [args.burst, "-options_file", deck, *common, "-max_steps", "2", "-checkpoint_interval", "1", "-checkpoint_keep", "1"])
        if proc is None or crashed(proc, text) or proc.returncode != 0:
            return False, f"second run into the folder failed (exit {proc.returncode if proc else 'hang'})"
        aside = glob.glob(os.path.join(out, "other_runs", "*"))
        if len(aside) != 1 or any(open(os.path.join(aside[0], c), "rb").read() != before[c] for c in cps if os.path.exists(os.path.join(aside[0], c))) or sorted(os.listdir(aside[0])) != cps:
            return False, "the first run's checkpoints are not all kept, byte for byte, in other_runs/<run id>/"
        proc, text = run(args, [args.burst, "-options_file", deck, *common, "-max_steps", "3", "-restart", out])
        if proc is not None and proc.returncode == 0 and "Restarted from" in text:
            return True, "the other run's checkpoints kept apart; -restart on the folder continues the second run"
        expect, what = r"^$", "a restart of the second run"
    else:  # option_change
        # (integer-valued options are counts or choices, -dim, -grid_cells: 1.5 times one is no valid input)
        physics = [i for i, (n, v) in enumerate(opts) if NUMBER.match(v) and not RUN_CONTROL.match(n) and float(v) != 0 and not re.fullmatch(r"[+-]?\d+", v)]
        if not physics:
            return True, "no numeric physics option (skipped)"
        i = rng.choice(physics)
        name, value = opts[i]
        changed = repr(float(value) * 1.5)
        proc, text = run(args, [args.burst, "-options_file", deck, *common, "-max_steps", "3", "-restart", cp, name, changed])
        expect, what = rf"other physics options than this run's .*{re.escape(name)} is '{re.escape(value)}' in the checkpoint, '{re.escape(changed)}' in this run", f"{name} {value} -> {changed}"
    if proc is None:
        return False, f"hang on restart ({what})"
    if crashed(proc, text):
        return False, f"restart crashed (exit {proc.returncode}; {what})"
    if proc.returncode == 0 or not re.search(expect, " ".join(error_message(text).split()) or text):
        return False, f"not refused as expected ({what}): exit {proc.returncode}: " + " ".join(error_message(text).split())[:300]
    return True, f"refused ({what})"


def concurrent_case(args, index, opts, work):
    base = os.path.join(work, f"case{index}")
    os.makedirs(base, exist_ok=True)
    deck = os.path.join(base, "case.opts")
    write_options(deck, opts)
    cmd = [args.burst, "-options_file", deck, "-output_dir", os.path.join(base, "out"), "-max_steps", "2", "-progress", "false", "-no_signal_handler"]
    procs = [subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace") for _ in range(2)]
    try:
        texts = [p.communicate(timeout=args.timeout)[0] for p in procs]
    except subprocess.TimeoutExpired:
        for p in procs:
            p.kill()
        return False, "hang"
    for p, t in zip(procs, texts):
        if crashed(p, t):
            return False, f"crashed (exit {p.returncode})"
        if "Could not rename" in t:
            return False, "a failed rename: the runs wrote the same files"
    rcs = [p.returncode for p in procs]
    refused = [t for t in texts if "in use by another run" in t]
    if rcs.count(0) == 2:
        return True, "both ran (the first was done before the second started)"
    if refused and 0 in rcs:
        return True, "one ran, one refused"
    if rcs.count(0) == 0 and all(error_message(t) for t in texts):
        return True, "the deck stops with a message (both runs or one refused)"
    return False, f"exits {rcs} without a lock refusal"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    p.add_argument("--cases", type=int, default=400)
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--only", type=int, default=None, help="run only this case number (replay)")
    p.add_argument("--timeout", type=float, default=120)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--verbose", action="store_true")
    p.add_argument("--classes", default=",".join(CLASSES), help="comma list of " + ", ".join(CLASSES))
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
    classes = [c for c in args.classes.split(",") if c]
    unknown = [c for c in classes if c not in CLASSES]
    if unknown:
        raise SystemExit(f"unknown class(es) {unknown}: choose among {', '.join(CLASSES)}")
    cases = []
    while len(cases) < args.cases:
        deck = rng.choice(decks)
        cls = rng.choice(classes) if len(classes) > 1 else classes[0]
        if cls == "values":
            m = mutate(parsed[deck], rng)
        else:  # the deck's options as they are, one fault of the class around them
            kind = rng.choice(CLASSES[cls])
            m = (parsed[deck], f"{kind}", kind, "", random.Random(rng.randrange(1 << 30)))
        if m:
            cases.append((len(cases), deck, *m))
    if args.only is not None:
        cases = [cases[args.only]]
    work = tempfile.mkdtemp(prefix="burst_fuzz_")
    failures = []

    def one(case):
        index, deck, opts, description, kind, name = case[:6]
        if kind in MUTATIONS:
            ok, what = run_case(args, index, deck, opts, description, kind, work)
        elif kind in CLASSES["files"]:
            ok, what = file_case(args, index, opts, kind, case[6], work)
        elif kind in CLASSES["checkpoints"]:
            ok, what = checkpoint_case(args, index, opts, kind, case[6], work)
        else:
            ok, what = concurrent_case(args, index, opts, work)
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
