#!/usr/bin/env python3
"""Checks the house's structure (README.md "Layout"): every include runs downward, folder and
sub-folder alike, from the libraries through experiments/ and apps/ to tests/ on top; no files
include each other in a loop; and no comment names a file that does not exist (a stale name
left by a rename). Prints each problem and exits 1; prints a one-line summary otherwise."""
import os
import re
import subprocess
import sys

# Pipeline order, bottom up: a file may include files of its own folder or of folders below.
# Each entry is a folder prefix; a file belongs to the longest prefix that holds it.
ORDER = [["core"], ["cuda"], ["engine/scene"], ["engine/oracle"], ["engine/raster"],
         ["engine/dsm"], ["strategies/storage", "strategies/voxelizer"], ["strategies/shadow"],
         ["render/io", "render/frame", "gl"], ["render/load"], ["experiments/harness"],
         ["experiments/advise"],
         ["experiments"], ["apps/common"], ["apps/viewer"], ["apps/deepvox"], ["tests"]]
LEVEL = {folder: level for level, folders in enumerate(ORDER) for folder in folders}
SOURCE = re.compile(r"\.(h|cpp|cu|cuh)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# Comments in C++ (// and block-comment lines) and in scripts and CMake files (#).
COMMENTED = re.compile(r"\.(h|cpp|cu|cuh|py|sh|cmake)$|(^|/)CMakeLists\.txt$")
CPP_COMMENT = re.compile(r"//(.*)$|^\s*/?\*+(.*)$")
HASH_COMMENT = re.compile(r"(?:^|\s)#(?!\s*include)(.*)$")
# A file named in a comment: a path with a folder, or a bare name with a source extension.
NAMED_FILE = re.compile(r"(?<![\w./$-])([\w./-]*[\w-]\.(?:h|cpp|cu|cuh|py|sh|json|md|cmake))\b")
# Names of files outside the repository (libraries, build outputs) that comments may cite.
EXTERNAL = {"cuda.h", "cuda_runtime.h", "taggedptr.h", "NanoVDB.h", "tiny_gltf.h", "git_sha.h"}


def folder_of(path):
    best = None
    for folder in LEVEL:
        if path == folder or path.startswith(folder + "/"):
            if best is None or len(folder) > len(best):
                best = folder
    return best


def tracked_files(root):
    out = subprocess.run(["git", "ls-files"], cwd=root, capture_output=True, text=True)
    if out.returncode == 0:
        return [f for f in out.stdout.splitlines() if os.path.isfile(os.path.join(root, f))]
    return [os.path.relpath(os.path.join(d, n), root) for d, _, names in os.walk(root)
            for n in names]


def check_includes(root, files):
    includes = {}
    for path in files:
        if SOURCE.search(path) and folder_of(path) and not path.startswith("results/"):
            with open(os.path.join(root, path), errors="replace") as f:
                includes[path] = INCLUDE.findall(f.read())
    problems = []
    for path, targets in sorted(includes.items()):
        here = folder_of(path)
        for target in targets:
            there = folder_of(target)
            if there and there != here and LEVEL[there] >= LEVEL[here]:
                problems.append(f"{path} includes {target}: {there}/ is not below {here}/")
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
    return problems, len(includes), sum(len(t) for t in includes.values())


def check_comments(root, files):
    present = set(files)
    basenames = {os.path.basename(f) for f in files}
    problems = []
    for path in files:
        if not COMMENTED.search(path) or path.startswith(("results/", "tests/fuzz/corpus/")):
            continue
        comment = CPP_COMMENT if SOURCE.search(path) else HASH_COMMENT
        with open(os.path.join(root, path), errors="replace") as f:
            for number, line in enumerate(f, 1):
                match = comment.search(line)
                if not match:
                    continue
                text = next(g for g in match.groups() if g is not None)
                for name in NAMED_FILE.findall(text):
                    if re.search(r"\b[A-Z]{2,}\b", name) or name in EXTERNAL:
                        continue  # a placeholder (NAME.json, DIR/report.md) or a library's file
                    if "/" in name:
                        near = os.path.normpath(os.path.join(os.path.dirname(path), name))
                        if name in present or near in present or name.rstrip("/") in present:
                            continue
                        if name.split("/")[0] not in {f.split("/")[0] for f in present}:
                            continue  # not a path into this repository
                    elif name in basenames or not SOURCE.search(name):
                        continue
                    problems.append(f"{path}:{number}: the comment names {name}, which does not exist")
    return problems


def main(root):
    files = tracked_files(root)
    problems, count, edges = check_includes(root, files)
    problems += check_comments(root, files)
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} problem(s): includes against the layer order, include loops or "
              "comments naming missing files", file=sys.stderr)
        return 1
    print(f"layers OK: {count} files, {edges} includes, every one downward, no loops; "
          "no comment names a missing file")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
