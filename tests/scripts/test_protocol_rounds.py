#!/usr/bin/env python3
"""Tests of scripts/protocol-rounds.sh with a stand-in deepvox (a shell script that records its
arguments, sleeps and exits as told): round k runs with order seed SEED + k - 1 and the suite's
arguments, a round that would end past the deadline is not begun (the first always runs), a
later command goes on from its FIRST round, and a failed round's exit code is the script's."""
import os
import subprocess
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "protocol-rounds.sh")
FAKE = """#!/bin/sh
echo "$@" >> "$FAKE_CALLS"
sleep "${FAKE_SLEEP:-0}"
exit "${FAKE_EXIT:-0}"
"""


class ProtocolRounds(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.fake = os.path.join(self.tmp.name, "deepvox")
        with open(self.fake, "w") as f:
            f.write(FAKE)
        os.chmod(self.fake, 0o755)
        self.calls = os.path.join(self.tmp.name, "calls.txt")
        self.out = os.path.join(self.tmp.name, "out")

    def tearDown(self):
        self.tmp.cleanup()

    def rounds(self, first, last, deadline, sleep=0, code=0):
        env = dict(os.environ, FAKE_CALLS=self.calls, FAKE_SLEEP=str(sleep), FAKE_EXIT=str(code))
        result = subprocess.run(
            ["bash", SCRIPT, self.fake, "accuracy", self.out, "100", str(first), str(last),
             str(deadline), "--backend", "cuda"], env=env, capture_output=True, text=True)
        calls = []
        if os.path.exists(self.calls):
            with open(self.calls) as f:
                calls = f.read().splitlines()
        return result, calls

    def test_each_round_gets_its_order_seed_and_the_suite_arguments(self):
        result, calls = self.rounds(1, 3, 600)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(calls, ["suite accuracy --no-report --order-seed %d --out %s "
                                 "--backend cuda" % (seed, self.out) for seed in (100, 101, 102)])
        for k in (1, 2, 3):
            self.assertTrue(os.path.exists(os.path.join(self.out, "round%d.log" % k)))

    def test_a_round_that_would_end_past_the_deadline_is_not_begun(self):
        result, calls = self.rounds(1, 5, 1, sleep=1)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(len(calls), 1)  # the first round always runs
        self.assertIn("stop before round 2", result.stdout)

    def test_a_later_command_goes_on_from_its_first_round(self):
        _, calls = self.rounds(4, 5, 600)
        self.assertEqual([c.split()[4] for c in calls], ["103", "104"])

    def test_a_failed_round_is_the_exit_code_and_the_next_rounds_still_run(self):
        result, calls = self.rounds(1, 2, 600, code=3)
        self.assertEqual(result.returncode, 3)
        self.assertEqual(len(calls), 2)


if __name__ == "__main__":
    unittest.main()
