#!/usr/bin/env python3
"""alignset.sampler, the sampler library from Python, on a table the real
CLI exported from a real server's cache: the four calls with NumPy arrays,
a pixel's points a function of (seed, pixel), an edge's direction found,
edge pixels below Owen-Sobol's error at the same total samples, and bad
input refused.

  ALIGNSET_SERVER_BIN=... ALIGNSET_CLI_BIN=... PYTHONPATH=build/python \\
      /usr/bin/python3 tests/python/test_sampler.py
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_client import start_server  # noqa: E402  (the same server start-up, event-driven)

import alignset  # noqa: E402
from alignset.sampler import AlignedSampler, SetTable, block_of  # noqa: E402

W = 16


def edge(theta_deg, cx, cy):
    """A straight edge through the image (pixels), f = 1 on the normal's side."""
    nx, ny = math.cos(math.radians(theta_deg)), math.sin(math.radians(theta_deg))
    return lambda x, y: (nx * (x - cx) + ny * (y - cy) > 0).astype(float)


def exact_area(theta_deg, cx, cy, px, py, grid=2048):
    """The edge's area in pixel (px, py), to 1e-6 (a fine midpoint grid)."""
    u = (np.arange(grid) + 0.5) / grid
    xs, ys = np.meshgrid(px + u, py + u)
    return float(edge(theta_deg, cx, cy)(xs, ys).mean())


class SamplerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="alignset-sampler-")
        cls.server, cls.log, cls.address = start_server(cls.dir)
        cli = os.environ["ALIGNSET_CLI_BIN"]
        subprocess.run([cli, "precompute", "--server", cls.address, "-n", "256", "--space", "1dir",
                        "--construction", "lattice"], check=True, capture_output=True)
        cls.table_path = os.path.join(cls.dir, "sets.tbl")
        subprocess.run([cli, "export", "--db", os.path.join(cls.dir, "cache.sqlite"), "-n", "256",
                        "-o", cls.table_path], check=True, capture_output=True)
        cls.table = SetTable.load(cls.table_path)
        cls.client = alignset.Client(cls.address, timeout=60)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.server.terminate()
        cls.server.wait(timeout=30)
        cls.log.close()
        shutil.rmtree(cls.dir, ignore_errors=True)

    def render(self, sampler, f, pixels):
        pre = {}
        for x in range(W):
            for y in range(W):
                p = sampler.prepass_points(x, y)
                pre[x, y] = f(x + p[:, 0], y + p[:, 1])
        out = {}
        for (x, y) in pixels:
            plan = sampler.plan(x, y, block_of(pre, x, y, sampler.block_radius))
            p = sampler.main_points(plan)
            self.assertEqual(p.shape, (sampler.n, 2))
            self.assertTrue(np.all((p >= 0) & (p < 1)))
            out[x, y] = (plan, sampler.estimate(plan, pre[x, y], f(x + p[:, 0], y + p[:, 1])))
        return out

    def test_the_table_holds_what_was_exported(self):
        self.assertEqual(self.table.sections(), [(256, "lattice", "1dir", 46)])
        self.assertEqual(self.table.point_counts("lattice"), [256])

    def test_points_are_a_function_of_seed_and_pixel(self):
        s = AlignedSampler(self.table, n=256, image_width=W)
        self.assertEqual((s.n, s.prepass_samples, s.block_radius), (256, 64, 1))
        a, b = s.prepass_points(3, 4), s.prepass_points(3, 4)
        np.testing.assert_array_equal(a, b)
        self.assertFalse(np.array_equal(a, s.prepass_points(4, 3)))
        other = AlignedSampler(self.table, n=256, image_width=W, seed=2)
        self.assertFalse(np.array_equal(a, other.prepass_points(3, 4)))

    def test_the_plan_reads_the_servers_lattice_for_the_edge(self):
        s = AlignedSampler(self.table, n=256, image_width=W)
        theta = 58.0
        (plan, _), = self.render(s, edge(theta, 8.3, 8.4), [(8, 8)]).values()
        self.assertGreaterEqual(plan.directions, 1)
        d = abs(plan.theta1_deg - theta) % 180
        self.assertLess(min(d, 180 - d), 3.0)
        kind, a, _ = plan.choice
        self.assertEqual(kind, "one")
        served = self.client.get_set(256, a, construction="lattice")
        self.assertEqual(plan.lattice_generator, served.metadata.lattice_generator)

    def test_edge_pixels_beat_owen_sobol_at_the_same_total(self):
        s = AlignedSampler(self.table, n=256, image_width=W)
        ours, theirs, count = 0.0, 0.0, 0
        for k, theta in enumerate([11.0, 47.0, 83.0, 119.0, 157.0]):
            cx, cy = 8.0 + 0.3 * k, 7.7
            f = edge(theta, cx, cy)
            pixels = [(x, y) for x in range(5, 11) for y in range(5, 11)
                      if 0.02 < exact_area(theta, cx, cy, x, y) < 0.98]
            for (x, y), (_, est) in self.render(s, f, pixels).items():
                truth = exact_area(theta, cx, cy, x, y)
                os_pts = self.client.samples("owen-sobol", 256 + 64, seed=1000 * k + 31 * x + y)
                ours += (est - truth) ** 2
                theirs += (f(x + os_pts[:, 0], y + os_pts[:, 1]).mean() - truth) ** 2
                count += 1
        self.assertGreater(count, 25)
        self.assertGreater(theirs / ours, 1.5, "Owen-Sobol at 320 over aligned 256 + 64: %.2f" % (theirs / ours))

    def test_bad_input_is_refused(self):
        with self.assertRaises(KeyError):
            AlignedSampler(self.table, n=1024, image_width=W)
        with self.assertRaises(ValueError):
            AlignedSampler(self.table, n=256, image_width=W, domain="sky")
        with self.assertRaises(ValueError):
            AlignedSampler(self.table, n=256, image_width=0)
        s = AlignedSampler(self.table, n=256, image_width=W)
        with self.assertRaises(ValueError):
            s.plan(2, 2, [np.zeros(64)] * 4)  # a 2 x 2 block where 3 x 3 is read
        plan = s.plan(2, 2, [np.zeros(64)] * 9)
        with self.assertRaises(ValueError):
            s.estimate(plan, np.zeros(10), np.zeros(256))
        bad = os.path.join(self.dir, "bad.tbl")
        with open(self.table_path, "rb") as src, open(bad, "wb") as dst:
            dst.write(src.read()[:-1])
        with self.assertRaises(RuntimeError) as e:
            SetTable.load(bad)
        self.assertIn("truncated", str(e.exception))


if __name__ == "__main__":
    unittest.main()
