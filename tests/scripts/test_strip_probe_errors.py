#!/usr/bin/env python3
"""Tests of scripts/strip_probe_errors.py: every samples/<item>.json below a folder (runs inside
runs too) loses its probe errors and keeps its timings; other files are left alone."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "strip_probe_errors.py")


class StripProbeErrors(unittest.TestCase):
    def test_probe_errors_go_and_timings_stay(self):
        with tempfile.TemporaryDirectory() as tmp:
            sample = {"timings": {"frame_ms": [1.0, 1.5]},
                      "probe_errors": {"surface": [0.1, -0.2]}}
            paths = [os.path.join(tmp, "samples", "3.json"),
                     os.path.join(tmp, "accuracy", "run2", "samples", "3.json")]
            for path in paths:
                os.makedirs(os.path.dirname(path))
                with open(path, "w") as f:
                    json.dump(sample, f)
            other = os.path.join(tmp, "meta.json")
            with open(other, "w") as f:
                json.dump({"probe_errors": 1}, f)
            result = subprocess.run([sys.executable, SCRIPT, tmp], capture_output=True,
                                    text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn("samples", result.stdout)
            for path in paths:
                with open(path) as f:
                    self.assertEqual(json.load(f), {"timings": {"frame_ms": [1.0, 1.5]}})
            with open(other) as f:
                self.assertEqual(json.load(f), {"probe_errors": 1})

    def test_no_folder_is_a_usage_error(self):
        result = subprocess.run([sys.executable, SCRIPT], capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("Usage", result.stderr)


if __name__ == "__main__":
    unittest.main()
