#!/usr/bin/env python3
"""Tests of scripts/check_comments.py: which comments it flags for naming an issue number (C++
line and block comments, # comments of Python, shell and CMake, Python docstrings; any case,
with or without '#', plural), what it lets pass (code and strings outside comments, words that
end in the same letters, fixture data), and that the repository itself passes."""
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CHECK = os.path.join(ROOT, "scripts", "check_comments.py")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import check_comments  # noqa: E402

# Spelled in two parts so that this file's own text never reads as a flagged comment.
WORD = "iss" + "ue"


def flagged(path, text):
    return [p.split(":")[1] for p in check_comments.problems_in(path, text)]


class Detection(unittest.TestCase):
    def test_cpp_line_and_block_comments(self):
        text = (f"// The planner ({WORD} 12): what a light needs\n"
                "int x = 1;  // a count\n"
                "/* start\n"
                f" * as {WORD.capitalize()} #41 says\n"
                " */\n")
        self.assertEqual(flagged("engine/a.h", text), ["1", "4"])

    def test_plural_and_no_space_forms(self):
        self.assertEqual(flagged("core/a.cpp", f"// {WORD}s 39 and 41\n// {WORD}#7\n"),
                         ["1", "2"])

    def test_hash_comments_of_scripts_and_cmake(self):
        self.assertEqual(flagged("tests/CMakeLists.txt", f"# Hard cases ({WORD} 14)\n"), ["1"])
        self.assertEqual(flagged("scripts/a.sh", f"echo hi  # see {WORD} 3\n"), ["1"])
        self.assertEqual(flagged("scripts/a.py", f"x = 1  # {WORD} 5\n"), ["1"])

    def test_python_docstrings(self):
        text = ('"""Writes the stand-ins.\n'
                f"For {WORD} 39's effects.\n"
                '"""\n'
                "def f():\n"
                f'    """One line, {WORD} 4."""\n')
        self.assertEqual(flagged("scripts/a.py", text), ["2", "5"])

    def test_code_strings_and_other_words_pass(self):
        text = (f'const char* s = "{WORD} 41";\n'
                "// tissue 0.2, the ventricles 0.0\n"
                f"// an {WORD} with the format, not a number\n")
        self.assertEqual(flagged("render/a.cpp", text), [])

    def test_fixture_data_and_results_are_not_checked(self):
        with tempfile.TemporaryDirectory() as root:
            for path in ["tests/fuzz/corpus/suite/x.cpp", "results/perf/run/run.sh", "core/a.h"]:
                os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
                with open(os.path.join(root, path), "w") as f:
                    f.write(f"// {WORD} 41\n" if path != "core/a.h" else "// fine\n")
            run = subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
            with open(os.path.join(root, "core/a.h"), "w") as f:
                f.write(f"// {WORD} 41\n")
            run = subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)
            self.assertEqual(run.returncode, 1)
            self.assertIn("core/a.h:1:", run.stdout)


class Repository(unittest.TestCase):
    def test_no_comment_in_the_repository_names_an_issue_number(self):
        run = subprocess.run([sys.executable, CHECK, ROOT], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)


if __name__ == "__main__":
    unittest.main()
