#!/usr/bin/python3
"""Checks that every C and C++ source of burst (src/, models/, tests/, scripts/) is as clang-format leaves it
under the project's .clang-format, and that no line is longer than its ColumnLimit. Fails naming
each file clang-format would change and each line over the limit (exit 1); fails when clang-format
is missing (scripts/install-deps.sh installs it).

To format after an edit:  clang-format -i <files>   (from the project root)
"""
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDERS = ("src", "models", "tests", "scripts")
SUFFIXES = (".cxx", ".hpp", ".h", ".c")


def sources():
    for folder in FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(ROOT, folder)):
            for f in sorted(files):
                if f.endswith(SUFFIXES):
                    yield os.path.join(dirpath, f)


def main():
    exe = shutil.which("clang-format")
    if exe is None:
        print("check_format: clang-format is not installed (scripts/install-deps.sh installs it)")
        return 1
    limit = int(re.search(r"^ColumnLimit:\s*(\d+)", open(os.path.join(ROOT, ".clang-format")).read(), re.M).group(1))
    files = list(sources())
    changed, long_lines = [], []
    for path in files:
        text = open(path, encoding="utf-8").read()
        formatted = subprocess.run([exe, "--style=file", "--assume-filename=" + path], input=text, capture_output=True, text=True, cwd=ROOT, check=True).stdout
        rel = os.path.relpath(path, ROOT)
        if formatted != text:
            changed.append(rel)
        for n, line in enumerate(text.split("\n"), 1):
            if len(line) > limit:
                long_lines.append(f"{rel}:{n}: {len(line)} characters")
    for rel in changed:
        print(f"  {rel}: not as clang-format leaves it (clang-format -i {rel})")
    for line in long_lines:
        print(f"  {line} (ColumnLimit {limit})")
    version = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip()
    print(f"check_format: {len(files)} files, {len(changed)} to reformat, {len(long_lines)} lines over {limit} characters ({version})")
    return 1 if changed or long_lines else 0


if __name__ == "__main__":
    sys.exit(main())
