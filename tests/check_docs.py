#!/usr/bin/env python3
"""Checks the user's manual: README.md and doc/*.md.

Fails (exit 1), naming file:line, when
  - a page speaks of the development history: the words "session", "round(s)" (as in a round of
    development; "round-off" and "round trip" are allowed), "this change", "previous commit";
  - README.md is longer than 350 lines;
  - a relative link or image points to a file that does not exist.

Run from anywhere: python3 tests/check_docs.py [ROOT] (ROOT defaults to the repository that holds
this script). Registered in tests/CMakeLists.txt as check_docs (label unit).
"""
import re
import sys
from pathlib import Path

MAX_README_LINES = 350

FORBIDDEN = [
    (re.compile(r"\bsessions?\b", re.IGNORECASE), "session"),
    # a round (of development); round-off, round off, round trip and round-trip stay allowed
    (re.compile(r"\brounds?\b(?![- ](?:off|trip)\b)", re.IGNORECASE), "round"),
    (re.compile(r"\bthis\s+change\b", re.IGNORECASE), "this change"),
    (re.compile(r"\bprevious\s+commit\b", re.IGNORECASE), "previous commit"),
]

# [text](target) and ![alt](target "title"); the text may hold one level of brackets.
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
INLINE_CODE = re.compile(r"`[^`]*`")
EXTERNAL = re.compile(r"^(?:[a-zA-Z][a-zA-Z0-9+.-]*:|//|#)")  # http:, https:, mailto:, anchors


def pages(root):
    out = [root / "README.md"]
    out += sorted((root / "doc").glob("*.md"))
    return [p for p in out if p.is_file()]


def check_page(root, page):
    errors = []
    rel = page.relative_to(root)
    lines = page.read_text(encoding="utf-8").split("\n")
    if lines and lines[-1] == "":
        lines = lines[:-1]
    if page.name == "README.md" and page.parent == root and len(lines) > MAX_README_LINES:
        errors.append(f"{rel}:{len(lines)}: README.md has {len(lines)} lines, more than {MAX_README_LINES}")
    in_fence = False
    for number, line in enumerate(lines, start=1):
        for pattern, word in FORBIDDEN:
            m = pattern.search(line)
            if m:
                errors.append(f"{rel}:{number}: speaks of development history ('{m.group(0)}'): {line.strip()}")
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        for m in LINK.finditer(INLINE_CODE.sub("", line)):
            target = m.group(1)
            if EXTERNAL.match(target):
                continue
            path = target.split("#", 1)[0].split("?", 1)[0]
            if not path:
                continue
            if not (page.parent / path).exists():
                errors.append(f"{rel}:{number}: link to a missing file: {target}")
    return errors


def main(argv):
    root = Path(argv[1]).resolve() if len(argv) > 1 else Path(__file__).resolve().parent.parent
    checked = pages(root)
    if not checked:
        print(f"check_docs: no README.md or doc/*.md under {root}")
        return 1
    errors = []
    for page in checked:
        errors += check_page(root, page)
    for e in errors:
        print(e)
    if errors:
        print(f"check_docs: {len(errors)} problem(s) in {len(checked)} page(s)")
        return 1
    print(f"check_docs: {len(checked)} page(s) clean (README.md {sum(1 for _ in open(root / 'README.md', encoding='utf-8'))} lines)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
