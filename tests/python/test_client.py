#!/usr/bin/env python3
"""The Python client (client/python/alignset) against the real alignset-server
on loopback: a set, a batch, the one-direction space, baseline samples, and
errors with the right status codes.

  ALIGNSET_SERVER_BIN=build/server/alignset-server PYTHONPATH=build/python \
      /usr/bin/python3 tests/python/test_client.py
"""
import ctypes
import math
import os
import select
import shutil
import subprocess
import tempfile
import threading
import time
import unittest

import grpc
import numpy as np

import alignset
from alignset.v1 import alignset_pb2 as pb


def read(path):
    with open(path) as f:
        return f.read()


IN_CLOSE_WRITE, IN_MOVED_TO = 0x8, 0x80


def wait_for_file_event(directory, ready, process, timeout):
    """Waits on events, not on a clock: ready() is asked now and after every
    file written or moved into `directory` (inotify, through libc), until it
    holds (True) or `process` exits or `timeout` seconds pass (False)."""
    libc = ctypes.CDLL(None, use_errno=True)
    fd = libc.inotify_init1(os.O_NONBLOCK | os.O_CLOEXEC)
    if fd >= 0 and libc.inotify_add_watch(fd, os.fsencode(directory), IN_CLOSE_WRITE | IN_MOVED_TO) < 0:
        os.close(fd)
        fd = -1
    exited = os.pidfd_open(process.pid)
    end = time.monotonic() + timeout
    try:
        while True:
            if ready():
                return True
            left = end - time.monotonic()
            if left <= 0 or process.poll() is not None:
                return ready()
            # Without inotify, a tenth of a second between looks is the fallback.
            wanted = [exited] + ([fd] if fd >= 0 else [])
            readable, _, _ = select.select(wanted, [], [], left if fd >= 0 else min(left, 0.1))
            if exited in readable:
                return ready()
            if fd in readable:
                try:
                    while os.read(fd, 4096):
                        pass
                except BlockingIOError:
                    pass
    finally:
        os.close(exited)
        if fd >= 0:
            os.close(fd)


def start_server(directory, listen="127.0.0.1:0", extra=()):
    """alignset-server on `listen` with its database in `directory`: (process, log, address)."""
    port_file = os.path.join(directory, "port")
    if os.path.exists(port_file):
        os.remove(port_file)
    log = open(os.path.join(directory, "server.log"), "a")
    server = subprocess.Popen(
        [os.environ["ALIGNSET_SERVER_BIN"], "--listen", listen, "--port-file", port_file,
         "--db", os.path.join(directory, "cache.sqlite"), "--max-iterations", "40",
         "--workers", "2", "--threads-per-worker", "1", "--max-n", "4096",
         "--log-level", "warn", *extra],
        stdout=log, stderr=log)
    # The server renames its port file into place once it listens.
    listening = lambda: os.path.exists(port_file) and read(port_file).strip() != ""
    if not wait_for_file_event(directory, listening, server, 30):
        server.kill()
        raise RuntimeError("alignset-server did not start: " + read(log.name))
    return server, log, "127.0.0.1:" + read(port_file).split()[0]


class ServerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="alignset-python-")
        cls.server, cls.log, cls.address = start_server(cls.dir)
        cls.client = alignset.Client(cls.address, timeout=60)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.server.terminate()
        cls.server.wait(timeout=30)
        cls.log.close()
        shutil.rmtree(cls.dir)

    def test_get_returns_a_numpy_set_in_the_unit_square(self):
        s = self.client.get_set(256, 30)
        self.assertEqual(s.points.shape, (256, 2))
        self.assertEqual(s.points.dtype, np.float64)
        self.assertTrue(np.all((s.points >= 0) & (s.points < 1)))
        self.assertEqual(list(s.metadata.served_deg), [30])
        self.assertEqual(s.metadata.key.phi1_deg, 30)
        # 60 degrees is the same canonical set with x and y swapped.
        swapped = self.client.get(256, 60)
        np.testing.assert_array_equal(swapped, s.points[:, ::-1])
        # Two directions.
        self.assertEqual(self.client.get(128, (12, 100)).shape, (128, 2))

    def test_batch_has_a_status_per_item(self):
        results = self.client.get_many([(64, 30), (8, 30), (64, (10, 20, 30)), (64, 120)])
        self.assertEqual(len(results), 4)
        self.assertIsInstance(results[0], alignset.AlignedSet)
        self.assertIsInstance(results[1], alignset.AlignSetError)
        self.assertEqual(results[1].code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertIn("below the minimum of 16", results[1].message)
        self.assertEqual(results[2].code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertTrue(results[3].metadata.swapped and results[3].metadata.inverted)
        np.testing.assert_array_equal(results[0].points, self.client.get(64, 30))

    def test_realizations(self):
        r = self.client.get_realizations(64, 30, 3)
        self.assertEqual(r.shape, (3, 64, 2))
        self.assertFalse(np.array_equal(r[0], r[1]))
        np.testing.assert_array_equal(r[0], self.client.get(64, 30))
        s = self.client.get_set(64, 30, realization=2)
        np.testing.assert_array_equal(s.points, r[2])
        self.assertEqual(s.metadata.key.realization, 2)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(64, 30, realization=64)
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)

    def test_one_direction_space(self):
        space = self.client.get_space(32)
        self.assertEqual(space.shape, (46, 32, 2))
        np.testing.assert_array_equal(space[17], self.client.get(32, 17))

    def test_lattice_construction(self):
        s = self.client.get_set(256, 30, construction="lattice")
        self.assertEqual(s.metadata.construction, "lattice")
        self.assertEqual(s.metadata.key.profile, "lattice-v2-w1")
        # A centred N-rooks set: one point in the middle of each column and row.
        cells = s.points * 256 - 0.5
        np.testing.assert_allclose(cells, np.round(cells), atol=1e-9)
        for axis in (0, 1):
            self.assertEqual(len(set(np.round(cells[:, axis]).astype(int))), 256)
        again = self.client.get_set(256, 30, construction="lattice")
        self.assertTrue(again.metadata.from_cache)
        np.testing.assert_array_equal(again.points, s.points)
        # The optimized set of the same key is another set under another profile.
        optimized = self.client.get_set(256, 30)
        self.assertEqual(optimized.metadata.construction, "optimized")
        self.assertNotEqual(optimized.metadata.key.profile, "lattice-v2-w1")
        self.assertFalse(np.array_equal(optimized.points, s.points))
        space = self.client.get_space(32, construction="lattice")
        self.assertEqual(space.shape, (46, 32, 2))
        np.testing.assert_array_equal(space[17], self.client.get(32, 17, construction="lattice"))
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(64, 30, construction="sobol")
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertIn("'lattice'", e.exception.message)

    def test_net_construction(self):
        s = self.client.get_set(64, 30, construction="net")
        self.assertEqual(s.metadata.construction, "net")
        self.assertEqual(s.metadata.key.profile, "net-v1-w1")
        # A (0,6,2)-net: every elementary interval of area 1/64 holds one point.
        for k in range(7):
            a = np.floor(s.points[:, 0] * 2 ** k).astype(int)
            b = np.floor(s.points[:, 1] * 2 ** (6 - k)).astype(int)
            self.assertEqual(len(set(zip(a, b))), 64)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(100, 30, construction="net")
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertIn("power of two", e.exception.message)

    def test_tent_lattice_construction(self):
        s = self.client.get_set(64, 30, construction="tent-lattice", realization=1)
        self.assertEqual(s.metadata.construction, "tent-lattice")
        self.assertEqual(s.metadata.key.profile, "tent-lattice-v1-w2")
        self.assertTrue(np.all((s.points >= 0) & (s.points < 1)))
        # Realizations are independent randomizations, each unbiased: the
        # mean of a non-periodic smooth function over them is its integral.
        sets = self.client.get_realizations(64, 30, 48, construction="tent-lattice")
        self.assertEqual(sets.shape, (48, 64, 2))
        np.testing.assert_array_equal(sets[1], s.points)
        q = np.mean(np.exp(sets[:, :, 0]) * sets[:, :, 1] ** 2, axis=1)
        self.assertGreater(np.std(q), 0)
        self.assertLess(abs(q.mean() - (np.e - 1) / 3), 4 * np.std(q) / np.sqrt(len(q)))

    def test_lattice_sequence_construction(self):
        # The first call searches the key's sequence (seconds alone, more on
        # a loaded machine); the later ones read the server's kept choice.
        s = self.client.get_set(128, 30, construction="lattice-sequence", timeout=600)
        self.assertEqual(s.metadata.construction, "lattice-sequence")
        self.assertEqual(s.metadata.key.profile, "lattice-sequence-v1-w1")
        longer = self.client.get(512, 30, construction="lattice-sequence")
        # The set for 128 is the first 128 points of the set for 512.
        np.testing.assert_array_equal(longer[:128], s.points)
        # Every power-of-two prefix is a shifted lattice: one point in each
        # of the 2^m columns, each at the same offset from its column's edge.
        for m in range(4, 10):
            x = longer[: 2 ** m, 0] * 2 ** m
            self.assertEqual(len(set(np.floor(x).astype(int))), 2 ** m)
            np.testing.assert_allclose(x - np.floor(x), (x - np.floor(x))[0], atol=1e-9)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(8, 30, construction="lattice-sequence")
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)

    def test_served_lattice_generator_and_own_shifts(self):
        # A plain lattice (120 degrees: swapped and mirrored) is its
        # generator's lattice under a shift: the one through its first point.
        s = self.client.get_set(64, 120, construction="lattice")
        g = s.metadata.lattice_generator
        self.assertTrue(0 < g < 64 and math.gcd(g, 64) == 1, g)
        own = alignset.lattice_points(64, g, s.points[0], False)
        key = lambda p: p[np.lexsort((p[:, 1], p[:, 0]))]
        np.testing.assert_allclose(key(own), key(s.points), atol=1e-12)
        self.assertEqual(self.client.get_set(64, 30, construction="optimized").metadata.lattice_generator, 0)
        # A tent-lattice: each pixel's own shift goes before the fold. Unbiased,
        # and on a smooth function that is not periodic on the square far
        # below a Cranley-Patterson shift of the served (folded) points.
        t = self.client.get_set(64, 30, construction="tent-lattice")
        g = t.metadata.lattice_generator
        self.assertTrue(0 < g < 64 and math.gcd(g, 64) == 1, g)
        f = lambda p: np.mean(np.exp(p[:, 0]) * p[:, 1] ** 2)
        rng = np.random.default_rng(5)
        before = np.array([f(alignset.lattice_points(64, g, rng.random(2), True)) for _ in range(64)])
        after = np.array([f(np.mod(t.points + rng.random(2), 1.0)) for _ in range(64)])
        exact = (np.e - 1) / 3
        self.assertLess(abs(before.mean() - exact), 4 * before.std() / 8 + 1e-15)
        self.assertLess(5 * before.var(), after.var())
        # The recipe's pixel_points does the same for any served set.
        shift = (0.3, 0.85)
        np.testing.assert_array_equal(t.pixel_points(shift),
                                      alignset.lattice_points(64, g, shift, True))
        o = self.client.get_set(64, 30)
        np.testing.assert_array_equal(o.pixel_points(shift), np.mod(o.points + shift, 1.0))
        with self.assertRaises(ValueError):
            o.pixel_points((0.2, 1.0))
        with self.assertRaises(ValueError):
            alignset.lattice_points(64, 2, (0.1, 0.2), True)
        with self.assertRaises(ValueError):
            alignset.lattice_points(64, 3, (1.0, 0.2), True)

    def test_baseline_samples(self):
        a = self.client.samples("owen-sobol", 64, seed=3)
        self.assertEqual(a.shape, (64, 2))
        np.testing.assert_array_equal(a, self.client.samples("owen-sobol", 64, seed=3))
        self.assertFalse(np.array_equal(a, self.client.samples("owen-sobol", 64, seed=3, shear=25)))

    def test_estimate_direction_then_get(self):
        # A step edge with normal 30 deg on a (H, W) = (48, 64) grid, rows along y.
        h, w = 48, 64
        y, x = np.mgrid[0:h, 0:w]
        x, y = (x + 0.5) / w - 0.5, (y + 0.5) / h - 0.5
        t = np.radians(30.0)
        grid = (x * np.cos(t) + y * np.sin(t) >= 0.05).astype(float)
        d = self.client.estimate_direction(grid)
        self.assertEqual(d.first.status, pb.DIRECTION_FOUND)
        self.assertLess(abs(d.first.theta_deg - 30.0), 1.0)
        # The transposed array is the mirror image: 90 - theta.
        self.assertLess(abs(self.client.estimate_direction(grid.T).first.theta_deg - 60.0), 1.0)
        s = self.client.get_set(64, d.first.theta_deg)
        self.assertEqual(s.points.shape, (64, 2))
        # Scattered samples of the same edge.
        rng = np.random.default_rng(3)
        p = rng.random((4096, 2))
        f = ((p[:, 0] - 0.5) * np.cos(t) + (p[:, 1] - 0.5) * np.sin(t) >= 0).astype(float)
        d = self.client.estimate_direction(f, points=p)
        self.assertLess(abs(d.first.theta_deg - 30.0), 3.0)
        # A constant patch has none; a NaN is refused.
        self.assertEqual(self.client.estimate_direction(np.ones((16, 16))).first.status,
                         pb.NO_DOMINANT_DIRECTION)
        grid[3, 4] = np.nan
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.estimate_direction(grid)
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)

    def test_errors_carry_the_status_code(self):
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(5000, 30)  # above this server's --max-n 4096
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertIn("maximum of 4096", e.exception.message)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(64, float("nan"))
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.samples("no-such-sampler", 64)
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get_many([(64, 30)] * 257)
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        # A per-call deadline shorter than an optimization.
        with self.assertRaises(alignset.AlignSetError) as e:
            self.client.get(4096, 7, timeout=0.01)
        self.assertEqual(e.exception.code, grpc.StatusCode.DEADLINE_EXCEEDED)
        # The server keeps serving.
        self.assertGreater(self.client.metrics().requests_invalid, 0)

    def test_a_call_sent_while_the_server_restarts_waits_for_it(self):
        directory = tempfile.mkdtemp(prefix="alignset-python-restart-")
        server, log, address = start_server(directory, extra=["--shutdown-grace", "1"])
        restarted = []
        try:
            with alignset.Client(address, timeout=60, connect_timeout=20) as c:
                first = c.get(64, 30)
                server.terminate()
                server.wait(timeout=30)
                # Down when the call goes out; on the same port and database 0.7 s later.
                restart = threading.Thread(target=lambda: (
                    time.sleep(0.7), restarted.append(start_server(directory, address))))
                restart.start()
                sent = time.monotonic()
                again = c.get_set(64, 30)
                waited = time.monotonic() - sent
                restart.join()
                self.assertGreaterEqual(waited, 0.7)
                self.assertTrue(again.metadata.from_cache)
                np.testing.assert_array_equal(again.points, first)
        finally:
            for p, l, _ in [(server, log, None)] + restarted:
                if p.poll() is None:
                    p.terminate()
                    p.wait(timeout=30)
                l.close()
            shutil.rmtree(directory)

    def test_a_bad_connect_timeout_is_refused(self):
        for bad in (-1, float("nan"), float("inf"), "2"):
            with self.assertRaises(ValueError):
                alignset.Client(self.address, connect_timeout=bad)

    def test_a_bad_call_timeout_is_refused_before_anything_is_sent(self):
        for bad in (-1, float("nan"), float("inf"), "2"):
            with self.assertRaises(ValueError):
                alignset.Client(self.address, timeout=bad)
        with alignset.Client("127.0.0.1:1", connect_timeout=0) as down:
            for bad in (-1, float("nan"), float("inf")):
                with self.assertRaises(ValueError):
                    down.get(64, 30, timeout=bad)

    def test_closing_a_client_leaves_no_error_in_grpcs_threads(self):
        # gRPC Python's connectivity poller raised "Channel closed!" on its
        # own thread when the channel closed under it (grpc issue 18995): a
        # traceback on every script's stderr although nothing had failed.
        errors = []
        hook = threading.excepthook
        threading.excepthook = lambda args: errors.append(args.exc_value)
        try:
            for _ in range(5):  # before the fix: an error almost every round
                with alignset.Client("127.0.0.1:1", timeout=5, connect_timeout=0.3) as down:
                    with self.assertRaises(alignset.AlignSetError):
                        down.get(64, 30)
                with alignset.Client(self.address) as up:
                    up.get(64, 30)
            time.sleep(0.5)  # not a wait for the server: gRPC's pollers get their next round
        finally:
            threading.excepthook = hook
        self.assertEqual(errors, [])

    def test_an_unreachable_server_is_unavailable(self):
        with alignset.Client("127.0.0.1:1", timeout=5) as down:
            with self.assertRaises(alignset.AlignSetError) as e:
                down.get(64, 30)
            self.assertEqual(e.exception.code, grpc.StatusCode.UNAVAILABLE)


if __name__ == "__main__":
    unittest.main(verbosity=2)
