#!/usr/bin/env python3
"""An evaluator of point sets that shares no code with alignset's core.

It reads point sets from files (UTK text, one "x y" a line, '#' comments;
several sets separated by '#' lines are read as one file per set here) and
measures, with NumPy only:

  edge D:      the Cranley-Patterson variance of step edges whose normal is
               theta + D degrees (D = 0, 0.5, 1, 2), averaged over 8 parallel
               edges at offsets in [-1/4, 1/4] and over both signs of D;
  gauss0:      the mean squared error, without any shift, over a fixed,
               seeded population of anisotropic Gaussians (sigma^2 in
               [0.01, 1] per axis, random rotation, centre anywhere in the
               square), the test an established suite runs;
  gauss-cp:    the same Gaussians under Cranley-Patterson shifts;
  ramp0/cp:    linear x + y and quadratic x^2 + y/2 ramps, without / with shifts.

Each sampler sees the same shifts and the same integrands. Several files for
one sampler (Owen-Sobol scrambles, lattice realizations) are averaged.

A sampler given with --randomized instead of --label is a randomization of
its own (the tent-folded lattice: shifted, then folded): its file holds many
'#'-separated realizations, and the edge, gauss0 and ramp0 columns are the
mean squared error over them with no shift added (the realizations are its
shifts); the -cp columns CP-shift the first 8 realizations as served, what a
user who shifts the set per pixel gets.

  construction_eval.py --theta 37 --label NAME FILE [FILE ...] [--label NAME FILE ...]
      [--randomized NAME FILE] [--shifts 512] [--gaussians 1024] [--out table.tsv]
  construction_eval.py --self-test   checks the evaluator against closed forms
"""
import argparse
import math
import sys

import numpy as np


def read_points(path):
    rows = []
    with open(path) as fh:
        for line in fh:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            x, y = line.split()[:2]
            rows.append((float(x), float(y)))
    return np.array(rows)


def read_sets(path):
    """The '#'-separated point sets of one file."""
    sets, rows = [], []
    with open(path) as fh:
        for line in fh:
            line = line.strip()
            if line.startswith("#"):
                if rows:
                    sets.append(np.array(rows))
                    rows = []
                continue
            if line:
                x, y = line.split()[:2]
                rows.append((float(x), float(y)))
    if rows:
        sets.append(np.array(rows))
    return sets


def clipped_area(theta_deg, offset):
    """Area of {p in [0,1]^2 : (p - c).n >= 0}, c = (1/2,1/2) + offset n,
    by clipping the square (Sutherland-Hodgman) and the shoelace formula."""
    n = np.array([math.cos(math.radians(theta_deg)), math.sin(math.radians(theta_deg))])
    c = np.array([0.5, 0.5]) + offset * n
    square = [np.array(p, float) for p in [(0, 0), (1, 0), (1, 1), (0, 1)]]
    out = []
    for i in range(4):
        a, b = square[i], square[(i + 1) % 4]
        da, db = (a - c) @ n, (b - c) @ n
        if da >= 0:
            out.append(a)
        if (da >= 0) != (db >= 0):
            out.append(a + da / (da - db) * (b - a))
    s = 0.0
    for i in range(len(out)):
        a, b = out[i], out[(i + 1) % len(out)]
        s += a[0] * b[1] - a[1] * b[0]
    return s / 2


def gauss_legendre_grid(k=96):
    x, w = np.polynomial.legendre.leggauss(k)
    x = 0.5 * (x + 1)
    w = 0.5 * w
    X, Y = np.meshgrid(x, x, indexing="ij")
    W = np.outer(w, w)
    return np.stack([X.ravel(), Y.ravel()], 1), W.ravel()


class Gaussians:
    def __init__(self, count, seed=20261125):
        rng = np.random.default_rng(seed)
        self.c = rng.random((count, 2))
        s2 = rng.uniform(0.01, 1.0, (count, 2))
        a = rng.uniform(0, math.pi, count)
        ca, sa = np.cos(a), np.sin(a)
        # A = R diag(1/s2) R^T
        self.a11 = ca * ca / s2[:, 0] + sa * sa / s2[:, 1]
        self.a22 = sa * sa / s2[:, 0] + ca * ca / s2[:, 1]
        self.a12 = ca * sa * (1 / s2[:, 0] - 1 / s2[:, 1])
        nodes, weights = gauss_legendre_grid()
        self.reference = np.array([weights @ self.values(nodes, k) for k in range(count)])

    def values(self, p, k):
        dx = p[:, 0] - self.c[k, 0]
        dy = p[:, 1] - self.c[k, 1]
        return np.exp(-0.5 * (self.a11[k] * dx * dx + 2 * self.a12[k] * dx * dy + self.a22[k] * dy * dy))

    def mean_values(self, p):
        """The estimate (mean over points) of every Gaussian."""
        out = np.empty(len(self.c))
        for k in range(len(self.c)):
            out[k] = self.values(p, k).mean()
        return out


RAMPS = [(lambda p: p[:, 0] + p[:, 1], 1.0), (lambda p: p[:, 0] ** 2 + 0.5 * p[:, 1], 1.0 / 3 + 0.25)]


def edge_variance(points, theta, deltas, shifts):
    """points: one set, CP-shifted by each of `shifts`; or, with shifts None,
    a list of realizations, each taken as it is."""
    offsets = np.linspace(-0.25, 0.25, 8)
    variants = points if shifts is None else [(points + s) % 1.0 for s in shifts]
    out = []
    for d in deltas:
        v = []
        for sign in ((1, -1) if d else (1,)):
            t = theta + sign * d
            n = np.array([math.cos(math.radians(t)), math.sin(math.radians(t))])
            for o in offsets:
                c = np.array([0.5, 0.5]) + o * n
                ref = clipped_area(t, o)
                est = np.array([np.mean(q @ n >= c @ n) for q in variants])
                v.append(np.mean((est - ref) ** 2))
        out.append(float(np.mean(v)))
    return out


def evaluate(points, theta, deltas, shifts, gaussians, gauss_shifts):
    r = {}
    for d, v in zip(deltas, edge_variance(points, theta, deltas, shifts)):
        r["edge %g" % d] = v
    r["gauss0"] = float(np.mean((gaussians.mean_values(points) - gaussians.reference) ** 2))
    cp = [np.mean((gaussians.mean_values((points + s) % 1.0) - gaussians.reference) ** 2) for s in gauss_shifts]
    r["gauss-cp"] = float(np.mean(cp))
    for name, (f, ref) in zip(("ramp1", "ramp2"), RAMPS):
        r[name + "0"] = float((f(points).mean() - ref) ** 2)
        r[name + "-cp"] = float(np.mean([(f((points + s) % 1.0).mean() - ref) ** 2 for s in shifts]))
    return r


def evaluate_randomized(sets, theta, deltas, shifts, gaussians, gauss_shifts):
    """The columns of evaluate() for a sampler randomized by its realizations."""
    r = {}
    for d, v in zip(deltas, edge_variance(sets, theta, deltas, None)):
        r["edge %g" % d] = v
    r["gauss0"] = float(np.mean([np.mean((gaussians.mean_values(p) - gaussians.reference) ** 2) for p in sets]))
    served = sets[:8]
    r["gauss-cp"] = float(np.mean([np.mean((gaussians.mean_values((p + s) % 1.0) - gaussians.reference) ** 2)
                                   for p in served for s in gauss_shifts]))
    for name, (f, ref) in zip(("ramp1", "ramp2"), RAMPS):
        r[name + "0"] = float(np.mean([(f(p).mean() - ref) ** 2 for p in sets]))
        r[name + "-cp"] = float(np.mean([(f((p + s) % 1.0).mean() - ref) ** 2 for p in served for s in shifts]))
    return r


def self_test():
    """The evaluator against what is known in closed form: one point under
    CP shifts has variance A (1 - A) on an indicator of area A (the edges'
    areas and tests), and the quadrature integrates an axis-aligned Gaussian
    to its erf product (the Gaussians' references)."""
    rng = np.random.default_rng(3)
    # One point under a uniform shift is a uniform point: variance A (1 - A).
    v = edge_variance(np.array([[0.3, 0.6]]), 30.0, [0], rng.random((20000, 2)))[0]
    offsets = np.linspace(-0.25, 0.25, 8)
    expected = np.mean([clipped_area(30.0, o) * (1 - clipped_area(30.0, o)) for o in offsets])
    ok = abs(v / expected - 1) < 0.03
    print("one point: %.4f against A(1-A) = %.4f: %s" % (v, expected, "ok" if ok else "FAIL"))
    # The same through realizations (--randomized): uniform one-point sets.
    vr = edge_variance(list(rng.random((20000, 1, 2))), 30.0, [0], None)[0]
    ok_r = abs(vr / expected - 1) < 0.03
    print("one point, realizations: %.4f against %.4f: %s" % (vr, expected, "ok" if ok_r else "FAIL"))
    ok = ok and ok_r
    nodes, weights = gauss_legendre_grid()
    s, c = 0.1, (0.3, 0.8)
    quad = weights @ np.exp(-0.5 * (((nodes[:, 0] - c[0]) / s) ** 2 + ((nodes[:, 1] - c[1]) / s) ** 2))
    one = [s * math.sqrt(math.pi / 2) * (math.erf((1 - ci) / (s * math.sqrt(2))) + math.erf(ci / (s * math.sqrt(2)))) for ci in c]
    exact = one[0] * one[1]
    ok_q = abs(quad - exact) < 1e-12
    print("quadrature: %.15f against %.15f: %s" % (quad, exact, "ok" if ok_q else "FAIL"))
    return 0 if ok and ok_q else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--theta", type=float, required=True)
    ap.add_argument("--shifts", type=int, default=512)
    ap.add_argument("--gaussians", type=int, default=1024)
    ap.add_argument("--gauss-shifts", type=int, default=8)
    ap.add_argument("--out")
    a, rest = ap.parse_known_args()
    groups, label = [], None
    it = iter(rest)
    for tok in it:
        if tok in ("--label", "--randomized"):
            label = next(it)
            groups.append((label, [], tok == "--randomized"))
        else:
            if not groups:
                sys.exit("construction_eval: a file before the first --label")
            groups[-1][1].append(tok)
    rng = np.random.default_rng(7)
    shifts = rng.random((a.shifts, 2))
    gauss_shifts = rng.random((a.gauss_shifts, 2))
    gaussians = Gaussians(a.gaussians)
    deltas = [0, 0.5, 1, 2]
    rows = []
    for label, files, randomized in groups:
        if randomized:
            sets = [p for f in files for p in read_sets(f)]
            mean = evaluate_randomized(sets, a.theta, deltas, shifts, gaussians, gauss_shifts)
            rows.append((label, len(sets[0]), len(sets), mean))
            continue
        per = [evaluate(read_points(f), a.theta, deltas, shifts, gaussians, gauss_shifts) for f in files]
        mean = {k: float(np.mean([p[k] for p in per])) for k in per[0]}
        n = len(read_points(files[0]))
        rows.append((label, n, len(files), mean))
    keys = list(rows[0][3].keys())
    lines = ["sampler\tN\tsets\ttheta\t" + "\t".join(keys)]
    for label, n, m, mean in rows:
        lines.append("%s\t%d\t%d\t%g\t" % (label, n, m, a.theta) + "\t".join("%.3e" % mean[k] for k in keys))
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if a.out:
        with open(a.out, "a") as fh:
            fh.write(text)


if __name__ == "__main__":
    sys.exit(main())
