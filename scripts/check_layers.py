#!/usr/bin/env python3
"""Checks that every include runs downward: a file may include files of its own folder or of
folders below it in the pipeline order (README.md "Layout"), and no files include each other
in a loop. Prints each offending include and exits 1; prints a one-line summary otherwise."""
import os
import re
import sys

ORDER = [["core"], ["cuda"], ["scene"], ["oracle"], ["renderer"], ["dsm"], ["strategies"],
         ["io"], ["frame", "gl"], ["generators"], ["load"], ["experiments"], ["apps"]]
LEVEL = {folder: level for level, folders in enumerate(ORDER) for folder in folders}
SOURCE = re.compile(r"\.(h|cpp|cu|cuh)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def main(root):
    includes = {}
    for top in LEVEL:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if SOURCE.search(name):
                    path = os.path.relpath(os.path.join(folder, name), root)
                    with open(os.path.join(root, path), errors="replace") as f:
                        includes[path] = INCLUDE.findall(f.read())
    problems = []
    for path, targets in sorted(includes.items()):
        here = path.split("/")[0]
        for target in targets:
            there = target.split("/")[0]
            if there in LEVEL and there != here and LEVEL[there] >= LEVEL[here]:
                problems.append(f"{path} includes {target}: {there}/ is not below {here}/")
    # Loops between files (depth-first search over the project's own includes).
    state = {}

    def visit(path, stack):
        state[path] = "open"
        stack.append(path)
        for target in includes.get(path, []):
            if target not in includes:
                continue
            if state.get(target) == "open":
                loop = stack[stack.index(target):] + [target]
                problems.append("include loop: " + " -> ".join(loop))
            elif target not in state:
                visit(target, stack)
        stack.pop()
        state[path] = "done"

    for path in sorted(includes):
        if path not in state:
            visit(path, [])
    for p in problems:
        print(p)
    edges = sum(len(t) for t in includes.values())
    if problems:
        print(f"{len(problems)} include(s) against the layer order or in loops", file=sys.stderr)
        return 1
    print(f"layers OK: {len(includes)} files, {edges} includes, every one downward, no loops")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
