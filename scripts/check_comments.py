#!/usr/bin/env python3
"""Checks that code comments say what and why, not where a change came from: no comment in a C++,
CUDA, Python, shell or CMake file names an issue number: the word issue (any case, plural too)
followed by a number, with or without '#'. An issue number means nothing to a reader of the code
and goes stale; the commit message and the issue tracker keep that history. Python docstrings
count as comments. Fixture data (tests/fuzz/corpus/, tests/data/malformed/) and the recorded
runs under results/ are not checked. Prints each problem as path:line and exits 1; prints a
one-line summary otherwise."""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_layers import COMMENTED, CPP_COMMENT, HASH_COMMENT, SOURCE, tracked_files  # noqa: E402

ISSUE_NUMBER = re.compile(r"\bissues?\s*#?\s*\d+", re.I)
SKIPPED = ("results/", "tests/fuzz/corpus/", "tests/data/malformed/")
DOCSTRING_QUOTES = ('"""', "'''")


def comment_lines(path, text):
    """(line number, comment text) for every comment in the file's text."""
    python = path.endswith(".py")
    comment = CPP_COMMENT if SOURCE.search(path) else HASH_COMMENT
    in_docstring = False
    for number, line in enumerate(text.splitlines(), 1):
        if python:
            quotes = sum(line.count(q) for q in DOCSTRING_QUOTES)
            if in_docstring or quotes:
                yield number, line
            if quotes % 2:
                in_docstring = not in_docstring
            if in_docstring:
                continue
        match = comment.search(line)
        if match:
            yield number, next(g for g in match.groups() if g is not None)


def problems_in(path, text):
    return [f"{path}:{number}: the comment names an issue number ('{match.group(0)}'); say "
            "what and why instead"
            for number, line in comment_lines(path, text)
            for match in [ISSUE_NUMBER.search(line)] if match]


def main(root):
    checked = 0
    problems = []
    for path in tracked_files(root):
        if not COMMENTED.search(path) or path.startswith(SKIPPED):
            continue
        with open(os.path.join(root, path), errors="replace") as f:
            problems += problems_in(path, f.read())
        checked += 1
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} comment(s) name an issue number", file=sys.stderr)
        return 1
    print(f"comments OK: {checked} files, no comment names an issue number")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
