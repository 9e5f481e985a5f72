#!/usr/bin/python3
"""Checks the layering of burst's sources from their #include lines (doc/architecture.md):

  models/    includes only models/ (and system or library headers): no grid, no swarm, no src/;
  src/mpm/   includes nothing of src/ice/, src/coupling/, src/scenes/ or the driver's simulation.hpp
             (the MPM solver, src/mpm/mpm.hpp, is a component the driver owns);
  src/ice/   includes nothing of src/mpm/, src/coupling/ or the driver's simulation.hpp;
  src/coupling/ includes nothing of the driver's simulation.hpp or src/scenes/ (it knows the two
             solvers it couples, not the run);
  so the MPM solver and the gas solver meet only in src/coupling/ (and the driver that owns both).

A quoted include is resolved as the compiler does: beside the including file, then in src/, then in
models/ (the include directories of CMakeLists.txt and Makefile.petsc). An include that resolves to
no file is reported too. `self_check` runs the rules on a made-up tree with one breach of each
rule and fails unless every breach is found. Exit 1 on any breach.
"""
import os
import re
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
RULES = [  # (folder of the including file, folders it may not include, why)
    ("models", ["src"], "models/ know no grid and no swarm: they include only models/"),
    ("src/mpm", ["src/ice", "src/coupling", "src/scenes", "src/simulation.hpp"], "the MPM solver knows no gas, coupling, scene or driver: MPM and ICE meet only in src/coupling/"),
    ("src/ice", ["src/mpm", "src/coupling", "src/simulation.hpp"], "MPM and ICE meet only in src/coupling/"),
    ("src/coupling", ["src/simulation.hpp", "src/scenes"], "the coupling knows the two solvers it couples, not the driver"),
]


def resolve(root, path, name):
    for base in (os.path.dirname(path), os.path.join(root, "src"), os.path.join(root, "models")):
        candidate = os.path.normpath(os.path.join(base, name))
        if os.path.isfile(candidate):
            return os.path.relpath(candidate, root)
    return None


def breaches(root):
    found = []
    for folder, forbidden, why in RULES:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for f in sorted(files):
                if not f.endswith((".hpp", ".cxx", ".h", ".c")):
                    continue
                path = os.path.join(dirpath, f)
                text = open(path, encoding="utf-8").read()
                for m in INCLUDE.finditer(text):
                    line = text.count("\n", 0, m.start()) + 1
                    target = resolve(root, path, m.group(1))
                    where = f"{os.path.relpath(path, root)}:{line}: #include \"{m.group(1)}\""
                    if target is None:
                        found.append(f"{where} resolves to no file")
                    elif any(target == b or target.startswith(b + "/") for b in forbidden):
                        found.append(f"{where} -> {target}: {why}")
    return found


def self_check():
    with tempfile.TemporaryDirectory() as root:
        files = {
            "src/simulation.hpp": "",
            "src/util.hpp": "",
            "src/mpm/swarm.hpp": "",
            "src/mpm/p2g.cxx": '#include "simulation.hpp"\n#include "../ice/ice.hpp"\n',
            "src/ice/ice.hpp": '#include "util.hpp"\n',
            "src/ice/step.cxx": '#include "ice.hpp"\n#include "../simulation.hpp"\n',
            "src/coupling/coupling.cxx": '#include "../ice/ice.hpp"\n#include "../mpm/p2g.cxx"\n#include "../simulation.hpp"\n',
            "models/material.hpp": '#include "util.hpp"\n',
            "models/elastic/model.cxx": '#include "../material.hpp"\n#include "../../src/mpm/swarm.hpp"\n',
        }
        for name, text in files.items():
            os.makedirs(os.path.join(root, os.path.dirname(name)), exist_ok=True)
            open(os.path.join(root, name), "w").write(text)
        found = breaches(root)
        expect = ["src/mpm/p2g.cxx:1", "src/mpm/p2g.cxx:2", "src/ice/step.cxx:2", "src/coupling/coupling.cxx:3", "models/material.hpp:1", "models/elastic/model.cxx:2"]
        for line in found:
            print("  found:", line)
        missed = [e for e in expect if not any(f.startswith(e + ":") for f in found)]
        extra = [f for f in found if not any(f.startswith(e + ":") for e in expect)]
        print(f"self check: {len(expect) - len(missed)} of {len(expect)} breaches found, {len(extra)} false alarms")
        return 1 if missed or extra else 0


def main():
    if sys.argv[1:] == ["self_check"]:
        return self_check()
    found = breaches(ROOT)
    for line in found:
        print(line)
    print(f"include rules: {len(found)} breach(es) in models/, src/mpm/, src/ice/, src/coupling/")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
