#!/usr/bin/env python3
"""Tests of experiments/harness/suite_fits.py, the line plots' fits (standard library only, so
they run without matplotlib): synthetic points of a known affine cost y = a + b x give back a and
b and a zero affine residual, while the power fit of the same points reads an exponent below 1
with a large residual; points of a known power law give back c and k; points with x or y not
positive are left out of both fits; fewer than three usable points or a single x give no fit."""
import math
import os
import sys
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "experiments", "harness"))
import suite_fits  # noqa: E402

# The exact oracle's frame on knecht-fig56 (H200): 86 ms fixed plus 61 ms per Mpx, over the
# scale suite's pixel counts (3:2, 0.15 to 8.6 Mpx).
MPX = [0.1536, 0.3456, 0.96, 2.16, 3.84, 8.64]


class AffineFit(unittest.TestCase):
    def test_a_fixed_plus_marginal_cost_gives_back_its_parts(self):
        points = [(x, 86.0 + 61.0 * x) for x in MPX]
        a, b = suite_fits.affine_fit(points)
        self.assertAlmostEqual(a, 86.0, places=9)
        self.assertAlmostEqual(b, 61.0, places=9)
        fit = suite_fits.fits(points)
        self.assertEqual(fit["points"], 6)
        self.assertLess(fit["affine"]["residual"], 1e-12)
        # The power fit of the same cost reads a sub-linear growth that is not there.
        self.assertAlmostEqual(fit["power"]["k"], 0.454, places=3)
        self.assertGreater(fit["power"]["residual"], 0.1)

    def test_least_squares_through_noisy_points(self):
        # y = 2 + 3x with residuals +1, -1, -1, +1 (orthogonal to 1 and x): a = 2, b = 3 exactly.
        points = [(0.0, 3.0), (1.0, 4.0), (2.0, 7.0), (3.0, 12.0)]
        a, b = suite_fits._least_squares(points)
        self.assertAlmostEqual(a, 2.0, places=12)
        self.assertAlmostEqual(b, 3.0, places=12)

    def test_a_power_law_gives_back_c_and_k(self):
        points = [(x, 5.0 * x ** 1.5, 0.0, 0.0) for x in (1.0, 2.0, 4.0, 8.0, 16.0, 32.0)]
        c, k = suite_fits.power_fit(points)
        self.assertAlmostEqual(c, 5.0, places=9)
        self.assertAlmostEqual(k, 1.5, places=9)
        fit = suite_fits.fits(points)
        self.assertLess(fit["power"]["residual"], 1e-12)
        self.assertGreater(fit["affine"]["residual"], 0.1)  # a line misses a convex curve

    def test_points_not_positive_are_left_out(self):
        points = [(0.0, 5.0), (1.0, 0.0), (-1.0, 3.0)] + [(x, 1.0 + 2.0 * x) for x in (1, 2, 3)]
        self.assertEqual(suite_fits.usable(points), [(1, 3.0), (2, 5.0), (3, 7.0)])
        a, b = suite_fits.affine_fit(points)
        self.assertAlmostEqual(a, 1.0, places=12)
        self.assertAlmostEqual(b, 2.0, places=12)

    def test_too_few_points_or_one_x_give_no_fit(self):
        self.assertIsNone(suite_fits.fits([(1.0, 2.0), (2.0, 3.0)]))
        self.assertIsNone(suite_fits.fits([(1.0, 2.0), (2.0, 3.0), (3.0, 0.0)]))
        self.assertIsNone(suite_fits.affine_fit([(2.0, 1.0), (2.0, 2.0), (2.0, 3.0)]))
        self.assertIsNone(suite_fits.power_fit([(2.0, 1.0), (2.0, 2.0), (2.0, 3.0)]))

    def test_the_description_names_both_fits(self):
        text = suite_fits.describe(suite_fits.fits([(x, 86.0 + 61.0 * x) for x in MPX]))
        self.assertTrue(text.startswith("k = 0.45 (residual 16.8 %); a + b x: a = 86, b = 61"),
                        text)
        self.assertFalse(math.isnan(suite_fits.fits([(x, 1.0) for x in MPX])["power"]["k"]))


if __name__ == "__main__":
    unittest.main()
