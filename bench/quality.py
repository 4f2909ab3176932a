#!/usr/bin/python3
"""Quality of aligned optimized sets on aligned step edges (issue: core optimizer).

For every N and θ: optimize a 3-direction set (0°, 90°, θ) with the alignset CLI,
measure the Cranley-Patterson-rotated variance of the step edge with normal θ
(4096 shifts) beside Owen-scrambled Sobol (mean of 16 scrambles, same shifts),
and the variance of the set optimized for θ + 45° on the same edge. Prints the
table, the ratios and the fitted log-log slopes; writes a PNG plot.

  /usr/bin/python3 bench/quality.py --n 256,1024,4096 --theta 10,30,45
"""
import argparse
import math
import os
import re
import subprocess
import sys


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}{r.stderr}")
    return r.stdout


def optimize(cli, n, theta, args, out_dir):
    path = os.path.join(out_dir, f"aligned_{args.profile}_n{n}_t{theta:g}.txt")
    if not os.path.exists(path) or args.force:
        cmd = [cli, "optimize", "--n", str(n), "--dir", f"{theta:g}", "--out", path,
               "--engine", args.engine, "--threads", str(args.threads), "--profile", args.profile]
        if args.max_iterations:
            cmd += ["--max-iterations", str(args.max_iterations)]
        out = run(cmd)
        secs = re.search(r"^time\s+([\d.]+) s", out, re.M).group(1)
        iters = re.search(r"^iterations\s+(\d+)", out, re.M).group(1)
        print(f"  optimized N={n} θ={theta:g}: {iters} iterations, {secs} s", flush=True)
    return path


def evaluate(cli, path, normal, shifts, scrambles):
    out = run([cli, "evaluate", path, "--normal", f"{normal:g}", "--shifts", str(shifts),
               "--scrambles", str(scrambles)])
    m = re.search(r"^variance\s+(\S+)\s+(\S+)", out, re.M)
    return float(m.group(1)), float(m.group(2))


def slope(ns, vs):
    xs = [math.log(n) for n in ns]
    ys = [math.log(v) for v in vs]
    k = len(xs)
    mx, my = sum(xs) / k, sum(ys) / k
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/cli/alignset")
    ap.add_argument("--n", default="256,1024,4096")
    ap.add_argument("--theta", default="10,30,45")
    ap.add_argument("--engine", default="auto")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-iterations", type=int, default=0)
    ap.add_argument("--shifts", type=int, default=4096)
    ap.add_argument("--scrambles", type=int, default=16)
    ap.add_argument("--profile", default="current", choices=["current", "supplement"])
    ap.add_argument("--out-dir", default="build/quality")
    ap.add_argument("--png", default="build/quality/quality.png")
    ap.add_argument("--force", action="store_true", help="re-optimize sets already on disk")
    args = ap.parse_args()
    ns = [int(x) for x in args.n.split(",")]
    thetas = [float(x) for x in args.theta.split(",")]
    os.makedirs(args.out_dir, exist_ok=True)

    rows = []
    for theta in thetas:
        for n in ns:
            aligned = optimize(args.cli, n, theta, args, args.out_dir)
            rotated = optimize(args.cli, n, theta + 45, args, args.out_dir)
            v_set, v_sobol = evaluate(args.cli, aligned, theta, args.shifts, args.scrambles)
            v_rot, _ = evaluate(args.cli, rotated, theta, args.shifts, args.scrambles)
            rows.append((theta, n, v_set, v_sobol, v_rot))

    print()
    print(f"{'θ':>5} {'N':>6} {'aligned':>11} {'owen-sobol':>11} {'set θ+45°':>11} "
          f"{'sobol/aligned':>14} {'θ+45/aligned':>13}")
    for theta, n, v, s, r in rows:
        print(f"{theta:5g} {n:6d} {v:11.4e} {s:11.4e} {r:11.4e} {s / v:14.2f} {r / v:13.2f}")
    print()
    print(f"{'θ':>5} {'slope aligned':>14} {'slope sobol':>12}")
    slopes = {}
    for theta in thetas:
        sub = [r for r in rows if r[0] == theta]
        sa = slope([r[1] for r in sub], [r[2] for r in sub])
        ss = slope([r[1] for r in sub], [r[3] for r in sub])
        slopes[theta] = (sa, ss)
        print(f"{theta:5g} {sa:14.3f} {ss:12.3f}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not available: no plot")
        return
    fig, ax = plt.subplots(figsize=(7, 5))
    for theta in thetas:
        sub = [r for r in rows if r[0] == theta]
        line, = ax.loglog([r[1] for r in sub], [r[2] for r in sub], "o-",
                          label=f"aligned θ={theta:g}° (slope {slopes[theta][0]:.2f})")
        ax.loglog([r[1] for r in sub], [r[3] for r in sub], "s--", color=line.get_color(), alpha=0.6,
                  label=f"Owen-Sobol θ={theta:g}° (slope {slopes[theta][1]:.2f})")
    ax.set_xlabel("N")
    ax.set_ylabel("CP-rotated variance, step edge with normal θ")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.dirname(args.png) or ".", exist_ok=True)
    fig.savefig(args.png, dpi=120)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
