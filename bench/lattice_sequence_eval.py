#!/usr/bin/env python3
"""Prefixes of the aligned lattice sequence against the fixed-size aligned
lattice of the same N and against Owen-Sobol (16 scrambles), judged by
bench/construction_eval.py's measures (NumPy, no code shared with the core):
step edges at theta + 0 / 0.5 / 1 / 2 degrees under Cranley-Patterson shifts,
seeded Gaussians and two ramps (non-periodic smooth functions) with shifts.

Every set comes from the command line (`alignset optimize --construction
lattice-sequence -n NMAX`, whose first N points are the prefix of N; `alignset
optimize --construction lattice -n N`; `alignset sample owen-sobol -n N`).
A CP-shifted set's variance does not depend on its own shift, so two
realizations of each lattice are enough; the shifts and Gaussians are the
evaluator's seeded ones, the same for every sampler.

  lattice_sequence_eval.py [--theta 7,19,34,52,68,86] [--n 64,96,...] [--big 65536]
      [--out bench/results/lattice_sequence/eval.tsv]
  lattice_sequence_eval.py --tables-only TSV   the summary from an earlier run
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import construction_eval as ce  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POW2 = [64, 128, 256, 512, 1024, 2048, 4096]
ARBITRARY = [96, 192, 384, 768, 1536, 3072, 100, 1000]


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("lattice_sequence_eval: %s failed: %s" % (" ".join(cmd), r.stderr))
    return r


def sets_of(path):
    return ce.read_sets(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--theta", default="7,19,34,52,68,86")
    ap.add_argument("--n", default=",".join(str(n) for n in sorted(POW2 + ARBITRARY)))
    ap.add_argument("--big", type=int, default=65536, help="also N = BIG with fewer shifts (0: not)")
    ap.add_argument("--shifts", type=int, default=256)
    ap.add_argument("--gaussians", type=int, default=256)
    ap.add_argument("--build", default=os.environ.get("BUILD_DIR", os.path.join(ROOT, "build")))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench/results/lattice_sequence/eval.tsv"))
    ap.add_argument("--tables-only", metavar="TSV")
    a = ap.parse_args()
    if a.tables_only:
        return summarize(a.tables_only)
    cli = os.path.join(a.build, "cli", "alignset")
    work = os.path.join(a.build, "lattice-sequence-eval")
    os.makedirs(work, exist_ok=True)
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    ns = [int(x) for x in a.n.split(",")]
    thetas = [float(x) for x in a.theta.split(",")]
    rng = np.random.default_rng(7)
    shifts = rng.random((a.shifts, 2))
    gauss_shifts = rng.random((8, 2))
    gaussians = ce.Gaussians(a.gaussians)
    deltas = [0, 0.5, 1, 2]
    rows = []

    def owen_sobol(n):
        out = []
        for s in range(1, 17):
            path = os.path.join(work, "os_%d_%d.txt" % (n, s))
            if not os.path.exists(path):
                run([cli, "sample", "owen-sobol", "-n", str(n), "-s", str(s), "-o", path])
            out.append(ce.read_points(path))
        return out

    def measure(label, theta, n, sets, sh):
        per = [ce.evaluate(p, theta, deltas, sh, gaussians, gauss_shifts) for p in sets]
        mean = {k: float(np.mean([q[k] for q in per])) for k in per[0]}
        rows.append((theta, n, label, mean))
        print("theta=%g N=%d %-18s edge0 %.3e edge1 %.3e gauss-cp %.3e" %
              (theta, n, label, mean["edge 0"], mean["edge 1"], mean["gauss-cp"]), flush=True)

    for theta in thetas:
        nmax = max(ns + ([a.big] if a.big else []))
        seq_path = os.path.join(work, "seq_%g.txt" % theta)
        r = run([cli, "optimize", "-n", str(nmax), "--dir", str(theta), "--construction", "lattice-sequence",
                 "-s", "1", "-m", "2", "-o", seq_path])
        with open(os.path.join(work, "seq_%g.levels" % theta), "w") as fh:
            fh.write(r.stderr)
        seq = sets_of(seq_path)
        # The other candidate the issue names: the aligned net, whose
        # power-of-two prefixes are nets, read as a (0,2)-sequence (its flips
        # chosen for 4096 points).
        net_path = os.path.join(work, "net4096_%g.txt" % theta)
        if not os.path.exists(net_path):
            run([cli, "optimize", "-n", "4096", "--dir", str(theta), "--construction", "net", "-s", "1", "-m", "2",
                 "-o", net_path])
        net = sets_of(net_path)
        for n in ns + ([a.big] if a.big else []):
            sh = shifts if n <= 4096 else shifts[:32]
            lat = []
            for s in (1, 2):
                path = os.path.join(work, "lat_%d_%g_%d.txt" % (n, theta, s))
                if not os.path.exists(path):
                    run([cli, "optimize", "-n", str(n), "--dir", str(theta), "--construction", "lattice", "-s", str(s),
                         "-o", path])
                lat.append(ce.read_points(path))
            measure("lattice-sequence", theta, n, [p[:n] for p in seq], sh)
            measure("lattice", theta, n, lat, sh)
            if n <= 4096:
                measure("net-prefix", theta, n, [p[:n] for p in net], sh)
            measure("owen-sobol", theta, n, owen_sobol(n), sh)
    keys = list(rows[0][3].keys())
    with open(a.out, "w") as fh:
        fh.write("theta\tN\tsampler\t" + "\t".join(keys) + "\n")
        for theta, n, label, mean in rows:
            fh.write("%g\t%d\t%s\t" % (theta, n, label) + "\t".join("%.4e" % mean[k] for k in keys) + "\n")
    print("wrote", a.out)
    return summarize(a.out)


def summarize(path):
    """Per N: the sequence's edge variance over the fixed-size lattice's and
    Owen-Sobol's over the sequence's, worst and geometric mean over the
    angles, on the edge itself and 1 degree off; the smooth columns beside."""
    data = {}
    with open(path) as fh:
        head = fh.readline().rstrip("\n").split("\t")
        for line in fh:
            f = line.rstrip("\n").split("\t")
            data[(float(f[0]), int(f[1]), f[2])] = dict(zip(head[3:], map(float, f[3:])))
    thetas = sorted({k[0] for k in data})
    ns = sorted({k[1] for k in data})
    lines = ["# Lattice sequence prefixes (bench/lattice_sequence_eval.py)", "",
             "Ratios of variances; seq = the aligned lattice sequence's first N points, lat = the fixed-size",
             "aligned lattice of N, OS = Owen-Sobol (16 scrambles), net-prefix = the first N points of the aligned "
             "net of 4096 (its prefixes are nets). Angles %s." % ", ".join("%g" % t for t in thetas),
             "Worst over the angles and (geometric mean). `seq/lat` under 1.5 and `OS/seq` over 3 are the goals.", "",
             "| N | seq/lat edge | seq/lat 1° off | OS/seq edge | OS/seq 1° off | net-prefix/lat edge | seq/lat Gaussians (CP) | OS/seq Gaussians | OS/seq ramp2 |",
             "|---|---|---|---|---|---|---|---|---|"]

    def col(n, num, den, key, worst):
        r = [data[(t, n, num)][key] / data[(t, n, den)][key] for t in thetas if (t, n, num) in data]
        if not r:
            return "-"
        g = math.exp(np.mean(np.log(r)))
        return "%.2f (%.2f)" % ((max(r) if worst == "max" else min(r)), g)

    for n in ns:
        lines.append("| %d%s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            n, "" if n & (n - 1) == 0 else " (not 2^m)",
            col(n, "lattice-sequence", "lattice", "edge 0", "max"),
            col(n, "lattice-sequence", "lattice", "edge 1", "max"),
            col(n, "owen-sobol", "lattice-sequence", "edge 0", "min"),
            col(n, "owen-sobol", "lattice-sequence", "edge 1", "min"),
            col(n, "net-prefix", "lattice", "edge 0", "max"),
            col(n, "lattice-sequence", "lattice", "gauss-cp", "max"),
            col(n, "owen-sobol", "lattice-sequence", "gauss-cp", "min"),
            col(n, "owen-sobol", "lattice-sequence", "ramp2-cp", "min")))
    text = "\n".join(lines) + "\n"
    md = os.path.splitext(path)[0] + ".md"
    with open(md, "w") as fh:
        fh.write(text)
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
