#!/usr/bin/env python3
"""Tests of the work-precision arithmetic of speed_vs_scipy.py (no timing):

    python3 -m unittest bvp/examples/test_speed_vs_scipy.py
"""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402

from speed_vs_scipy import bratu_state_exact, pareto, scene_error, time_at_error  # noqa: E402


class Pareto(unittest.TestCase):
    def test_dominated_and_invalid_points_are_dropped(self):
        points = [(1e-6, 1.0), (1e-8, 4.0), (1e-7, 5.0), (1e-9, float("nan")), (0.0, 0.1), (1e-5, 2.0)]
        # (1e-7, 5.0) is beaten by (1e-8, 4.0); (1e-5, 2.0) by (1e-6, 1.0)
        self.assertEqual(pareto(points), [(1e-8, 4.0), (1e-6, 1.0)])

    def test_front_has_increasing_error_and_decreasing_time(self):
        rng = np.random.default_rng(3)
        points = list(zip(10.0 ** rng.uniform(-12, -4, 40), rng.uniform(0.1, 10, 40)))
        front = pareto(points)
        self.assertTrue(all(a[0] < b[0] and a[1] > b[1] for a, b in zip(front, front[1:])))
        for e, t in points:  # every point is matched or beaten by a front point
            self.assertTrue(any(fe <= e and ft <= t for fe, ft in front))


class TimeAtError(unittest.TestCase):
    def test_power_law_is_interpolated_exactly(self):
        # time = error^(-1/4): log-log linear, so any interior error is exact
        front = pareto([(e, e ** -0.25) for e in (1e-4, 1e-6, 1e-8, 1e-10)])
        for e in (1e-4, 3e-5, 1e-7, 4.47e-10, 1e-10):
            self.assertAlmostEqual(time_at_error(front, e), e ** -0.25, delta=1e-9 * e ** -0.25)

    def test_between_points_it_is_the_geometric_interpolation(self):
        front = [(1e-10, 8.0), (1e-8, 2.0)]
        self.assertAlmostEqual(time_at_error(front, 1e-9), 4.0)

    def test_no_extrapolation(self):
        front = [(1e-10, 8.0), (1e-8, 2.0)]
        self.assertIsNone(time_at_error(front, 9e-11))
        self.assertIsNone(time_at_error(front, 2e-8))
        self.assertIsNone(time_at_error([], 1e-9))
        self.assertEqual(time_at_error([(1e-9, 3.0)], 1e-9), 3.0)


class SceneError(unittest.TestCase):
    def test_largest_relative_deviation(self):
        ref = [0.05, -0.2, 100.0, 80.0]
        self.assertEqual(scene_error(ref, ref), 0.0)
        self.assertAlmostEqual(scene_error([0.05, -0.2002, 100.0, 80.0], ref), 1e-3, delta=1e-15)
        self.assertAlmostEqual(scene_error([0.0505, -0.2002, 100.0, 80.0], ref), 1e-2, delta=1e-15)


class BratuExact(unittest.TestCase):
    def test_state_solves_the_bvp(self):
        lam = 3.51
        # lower-branch theta: theta = sqrt(2 lam) cosh(theta / 4), by bisection on
        # [0, theta at the fold] (theta/4 tanh(theta/4) = 1 there, theta = 4.7987)
        lo, hi = 0.0, 4.7987
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid - math.sqrt(2 * lam) * math.cosh(mid / 4) < 0:
                lo = mid
            else:
                hi = mid
        th = 0.5 * (lo + hi)
        x = np.linspace(0, 1, 401)
        y, dy = bratu_state_exact(x, th)
        self.assertLess(max(abs(y[0]), abs(y[-1])), 1e-14)
        # y' is the derivative of y, and y'' = -lam e^y (central differences)
        h = x[1] - x[0]
        self.assertLess(np.max(np.abs(np.gradient(y, h)[1:-1] - dy[1:-1])), 1e-3)
        d2 = (dy[2:] - dy[:-2]) / (2 * h)
        self.assertLess(np.max(np.abs(d2 + lam * np.exp(y[1:-1]))), 1e-3)


if __name__ == "__main__":
    unittest.main()
