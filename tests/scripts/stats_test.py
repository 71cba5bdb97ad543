#!/usr/bin/env python3
"""scripts/stats.py against published values: R's prop.test (Wilson),
Fisher's tea-tasting table and SciPy's documented examples (Fisher,
Kruskal-Wallis), chi-square tables."""

import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..',
                                'scripts'))
import stats  # noqa: E402


class StatsTest(unittest.TestCase):
    def test_wilson(self):
        lo, hi = stats.wilson(8, 12)
        self.assertAlmostEqual(lo, 0.3906, places=4)
        self.assertAlmostEqual(hi, 0.8619, places=4)
        self.assertEqual(stats.wilson(0, 0), (0.0, 1.0))
        lo, hi = stats.wilson(0, 10)
        self.assertEqual(lo, 0.0)
        self.assertAlmostEqual(hi, 0.2775, places=4)
        with self.assertRaises(ValueError):
            stats.wilson(3, 2)

    def test_fisher(self):
        self.assertAlmostEqual(stats.fisher_exact([[3, 1], [1, 3]]),
                               0.4857142857, places=9)
        self.assertAlmostEqual(stats.fisher_exact([[8, 2], [1, 5]]),
                               0.0349650350, places=9)
        self.assertAlmostEqual(stats.fisher_exact([[6, 2], [1, 4]]),
                               0.1025641026, places=9)
        self.assertEqual(stats.fisher_exact([[0, 0], [0, 0]]), 1.0)
        self.assertEqual(stats.fisher_exact([[5, 0], [5, 0]]), 1.0)

    def test_chi2(self):
        self.assertAlmostEqual(stats.chi2_sf(3.841458820694124, 1), 0.05,
                               places=12)
        self.assertAlmostEqual(stats.chi2_sf(5.991464547107979, 2), 0.05,
                               places=12)
        self.assertAlmostEqual(stats.chi2_sf(7.0, 2), 0.0301973834223185,
                               places=14)
        # Even df: P(X > x) = exp(-x/2) sum_{k < df/2} (x/2)^k / k!.
        for x, df in [(30.0, 10), (0.5, 4), (100.0, 60), (12.3, 2)]:
            half = x / 2
            closed = math.exp(-half) * sum(
                half ** k / math.factorial(k) for k in range(df // 2))
            self.assertAlmostEqual(stats.chi2_sf(x, df) / closed, 1.0,
                                   places=11)
        self.assertEqual(stats.chi2_sf(0.0, 3), 1.0)

    def test_kruskal_wallis(self):
        h, p = stats.kruskal_wallis([1, 3, 5, 7, 9], [2, 4, 6, 8, 10])
        self.assertAlmostEqual(h, 0.2727272727, places=9)
        self.assertAlmostEqual(p, 0.6015081344405895, places=12)
        h, p = stats.kruskal_wallis([1, 1, 1], [2, 2, 2], [2, 2])
        self.assertAlmostEqual(h, 7.0, places=12)
        self.assertAlmostEqual(p, 0.0301973834223185, places=14)
        self.assertEqual(stats.kruskal_wallis([4, 4], [4]), (0.0, 1.0))
        with self.assertRaises(ValueError):
            stats.kruskal_wallis([1, 2])

    def test_holm(self):
        # As R's p.adjust(p, "holm"), worked by hand: sorted p times
        # m, m - 1, ..., then a running maximum, capped at 1.
        adjusted = stats.holm([0.01, 0.02, 0.03, 0.04, 0.05])
        for got, want in zip(adjusted, [0.05, 0.08, 0.09, 0.09, 0.09]):
            self.assertAlmostEqual(got, want, places=12)
        adjusted = stats.holm([0.04, 0.01, 0.5])
        for got, want in zip(adjusted, [0.08, 0.03, 0.5]):
            self.assertAlmostEqual(got, want, places=12)
        self.assertEqual(stats.holm([0.6, 0.7]), [1.0, 1.0])
        self.assertEqual(stats.holm([]), [])


if __name__ == '__main__':
    unittest.main()
