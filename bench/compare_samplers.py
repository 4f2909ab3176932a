#!/usr/bin/python3
"""Variance of CP-rotated step-edge estimates against N for every sampler.

Drives the `alignset` binary:
  alignset sample KIND --n N --seed S [--shear DEG] --out FILE
  alignset optimize --n N --dir PHI [--max-iterations K] --engine E --out FILE
  alignset align FILE --canonical PHI --dir DEG --out FILE
  alignset variance FILE... --normal DEG... --shifts K

For edge normals THETA (spectral directions; default 20, 70, 110, 160: one per
quadrant, so the four group elements of Algorithm 1 are all exercised on one
canonical set phi = 20) it measures, at N = 4^k between --n-min and --n-max:
  - every registered sampler (mean over --seeds seeds),
  - pmj02bn sheared onto each THETA (Algorithm 2),
  - an optimized canonical set for phi(THETA), aligned onto each THETA,
prints a table of variance (mean over seeds and normals) with fitted log-log
slopes, checks that the aligned optimized sets beat sheared pmj02bn and
Owen-Sobol at every N >= 1024, and writes a log-log PNG.

Usage:
  /usr/bin/python3 bench/compare_samplers.py --n-max 4096 [--iterations 1500]
The optimization dominates the cost (direct engine: ~3.5 ms/iteration at
N = 1024, ~55 ms at 4096, ~16x per 4x N); use --engine fast once it exists,
or --opt-n-max to stop optimizing above some N. Optimized canonical sets are
kept in --workdir by (phi, N, iterations, engine, optimizer defaults version)
and reused by later runs; delete them to re-optimize.
"""

import argparse
import math
import os
import subprocess
import sys
import time
from collections import defaultdict

import numpy as np

SQUARE_ONLY = {"grid", "uniform-jitter", "jittered"}
SEEDLESS = {"grid", "halton", "hammersley", "sobol"}


def run(cmd, quiet=True):
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("command failed (%d): %s\n%s" % (res.returncode, " ".join(cmd), res.stderr.strip()))
    return res.stdout


def canonical_phi(theta):
    """Algorithm 1: the canonical direction serving a whole-degree normal."""
    t = int(round(theta % 180.0)) % 180
    if t <= 45:
        return t
    if t <= 90:
        return 90 - t
    if t <= 135:
        return t - 90
    return 180 - t


def variance_of(binary, files, normals, shifts, seed):
    """{(file, normal): variance} via `alignset variance`, in batches."""
    out = {}
    batch = 64
    for i in range(0, len(files), batch):
        cmd = [binary, "variance"] + files[i:i + batch] + ["--shifts", str(shifts), "--seed", str(seed)]
        for d in normals:
            cmd += ["--normal", repr(float(d))]
        for line in run(cmd).splitlines():
            if line.startswith("#") or not line.strip():
                continue
            path, _n, normal, var, _se = line.split("\t")
            out[(path, float(normal))] = float(var)
    return out


def slope(ns, vs):
    x = np.log(np.asarray(ns, float))
    y = np.log(np.asarray(vs, float))
    return float(np.polyfit(x, y, 1)[0]) if len(ns) >= 2 else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--alignset", default=os.path.join(here, "..", "build", "client", "alignset"))
    ap.add_argument("--n-min", type=int, default=256)
    ap.add_argument("--n-max", type=int, default=4096, help="largest N (powers of 4: 256 ... 16384)")
    ap.add_argument("--opt-n-max", type=int, default=None, help="largest N to optimize (default --n-max)")
    ap.add_argument("--normals", default="20,70,110,160", help="edge normals in degrees (spectral directions)")
    ap.add_argument("--seeds", type=int, default=4, help="seeds per randomized sampler")
    ap.add_argument("--shifts", type=int, default=4096, help="Cranley-Patterson shifts per estimate")
    ap.add_argument("--iterations", type=int, default=0,
                    help="optimizer iterations per set (0: the optimizer's default budget)")
    ap.add_argument("--engine", default="direct", help="spectral engine for optimize (direct, fast, cuda, auto)")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--samplers", default="all", help="comma-separated registry names, or 'all'")
    ap.add_argument("--workdir", default="/tmp/alignset_compare")
    ap.add_argument("--png", default=None, help="output plot (default WORKDIR/compare_samplers.png)")
    args = ap.parse_args()

    binary = os.path.abspath(args.alignset)
    if not os.access(binary, os.X_OK):
        sys.exit("no alignset binary at %s (build it: ninja -C build alignset)" % binary)
    os.makedirs(args.workdir, exist_ok=True)
    png = args.png or os.path.join(args.workdir, "compare_samplers.png")
    normals = [float(x) for x in args.normals.split(",")]
    ns = [4 ** k for k in range(1, 12) if args.n_min <= 4 ** k <= args.n_max]
    if not ns:
        sys.exit("no power of 4 in [--n-min, --n-max]")
    opt_n_max = args.opt_n_max if args.opt_n_max is not None else args.n_max

    listing = run([binary, "sample", "--list"])
    registry = [l.split()[0] for l in listing.splitlines() if l.startswith("  ") and not l.startswith("  --")
                and not l.startswith("   ")]
    samplers = registry if args.samplers == "all" else args.samplers.split(",")

    # variance[method][N] = mean over seeds and normals
    variance = defaultdict(dict)
    timings = {}

    for n in ns:
        t0 = time.time()
        # Isotropic and axis-aligned samplers: one file per (sampler, seed),
        # measured on every normal.
        files, owner = [], {}
        for name in samplers:
            seeds = [1] if name in SEEDLESS else range(1, args.seeds + 1)
            for s in seeds:
                path = os.path.join(args.workdir, "%s_%d_%d.txt" % (name, n, s))
                run([binary, "sample", name, "--n", str(n), "--seed", str(s), "--out", path])
                files.append(path)
                owner[path] = name
        var = variance_of(binary, files, normals, args.shifts, 7)
        acc = defaultdict(list)
        for (path, _d), v in var.items():
            acc[owner[path]].append(v)
        for name, vs in acc.items():
            variance[name][n] = float(np.mean(vs))

        # pmj02bn sheared onto each normal.
        sheared = defaultdict(list)
        for d in normals:
            sfiles = []
            for s in range(1, args.seeds + 1):
                path = os.path.join(args.workdir, "pmj02bn_shear%g_%d_%d.txt" % (d, n, s))
                run([binary, "sample", "pmj02bn", "--n", str(n), "--seed", str(s), "--shear", repr(d), "--out", path])
                sfiles.append(path)
            for v in variance_of(binary, sfiles, [d], args.shifts, 7).values():
                sheared[n].append(v)
        variance["pmj02bn sheared"][n] = float(np.mean(sheared[n]))

        # Optimized canonical sets, aligned onto each normal.
        if n <= opt_n_max:
            canon = {}
            topt = time.time()
            for phi in sorted({canonical_phi(d) for d in normals}):
                # v2: the optimizer defaults of algorithm version 2 (c = 4N, budget by N).
                path = os.path.join(args.workdir, "opt_v2_phi%d_%d_it%d_%s.txt" % (phi, n, args.iterations, args.engine))
                if not os.path.exists(path):
                    cmd = [binary, "optimize", "--n", str(n), "--dir", str(phi), "--seed", "1",
                           "--engine", args.engine, "--out", path]
                    if args.iterations:
                        cmd += ["--max-iterations", str(args.iterations)]
                    if args.threads:
                        cmd += ["--threads", str(args.threads)]
                    run(cmd)
                canon[phi] = path
            timings[n] = time.time() - topt
            aligned = []
            for d in normals:
                phi = canonical_phi(d)
                path = os.path.join(args.workdir, "aligned_%g_%d.txt" % (d, n))
                run([binary, "align", canon[phi], "--canonical", str(phi), "--dir", repr(d), "--out", path])
                aligned += list(variance_of(binary, [path], [d], args.shifts, 7).values())
            variance["aligned optimized"][n] = float(np.mean(aligned))
        print("N=%d measured in %.1f s%s" % (n, time.time() - t0,
              " (optimization %.1f s)" % timings[n] if n in timings else ""), file=sys.stderr)

    # Table.
    methods = [m for m in samplers if m in variance] + ["pmj02bn sheared", "aligned optimized"]
    methods = [m for m in methods if m in variance]
    print("CP-rotated variance of step edges with normals %s deg (spectral direction = edge normal);"
          % ", ".join("%g" % d for d in normals))
    print("mean over %d seeds (1 for seedless samplers and the optimized set) and the normals, %d shifts"
          % (args.seeds, args.shifts))
    print("optimized: %s iterations, engine %s"
          % (args.iterations or "default (1000 up to N = 4096, then like sqrt N)", args.engine))
    header = "%-22s" % "sampler" + "".join("%12s" % ("N=%d" % n) for n in ns) + "%9s" % "slope"
    print(header)
    print("-" * len(header))
    slopes = {}
    for m in methods:
        row_ns = [n for n in ns if n in variance[m]]
        slopes[m] = slope(row_ns, [variance[m][n] for n in row_ns])
        cells = "".join("%12.3e" % variance[m][n] if n in variance[m] else "%12s" % "-" for n in ns)
        print("%-22s%s%9.2f" % (m, cells, slopes[m]))

    # The acceptance check: aligned optimized beats sheared pmj02bn and
    # Owen-Sobol at every N >= 1024 that was optimized.
    ok = True
    checked = False
    for n in ns:
        if n < 1024 or n not in variance["aligned optimized"]:
            continue
        checked = True
        a = variance["aligned optimized"][n]
        for rival in ("pmj02bn sheared", "owen-sobol"):
            if rival in variance and n in variance[rival]:
                r = variance[rival][n]
                verdict = "beats" if a < r else "DOES NOT beat"
                ok &= a < r
                print("N=%d: aligned optimized %.3e %s %s %.3e (ratio %.2f)" % (n, a, verdict, rival, r, r / a))
    if checked:
        print("check (aligned optimized beats sheared pmj02bn and owen-sobol at every N >= 1024): %s"
              % ("PASS" if ok else "FAIL"))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(9, 6.5))
    for i, m in enumerate(methods):
        row_ns = [n for n in ns if n in variance[m]]
        color = "black" if m == "aligned optimized" else plt.cm.tab20(i % 20)
        style = "-" if m in ("aligned optimized", "pmj02bn sheared", "owen-sobol", "random") else "--"
        width = 2.5 if m == "aligned optimized" else 1.2
        ax.loglog(row_ns, [variance[m][n] for n in row_ns], style, marker="o", markersize=3, linewidth=width,
                  color=color, label="%s (%.2f)" % (m, slopes[m]))
    ax.set_xlabel("N")
    ax.set_ylabel("variance (CP rotation)")
    ax.set_title("Step edges, normals %s deg" % ", ".join("%g" % d for d in normals))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print("wrote %s" % png)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
