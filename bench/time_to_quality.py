#!/usr/bin/python3
"""Time to quality: how long a default optimization takes to get within a given
fraction of a fully converged set (issue: fast spectral engines).

For each seed, a 3-direction set (0°, 90°, θ) of N points is optimized three
ways with the alignset CLI:
  - fully converged, c = 4N (the default SW weight): no iteration budget to
    speak of, the run ends when the plateau rule has driven the learning rate
    under its floor;
  - fully converged, c = N (the weight before the schedule change);
  - with the default options (the timed run).
Each set's Cranley-Patterson-rotated variance on the aligned step edge is
measured with `alignset evaluate` (8 parallel edges, 4096 shifts). The
reference is the *lower* of the two converged means over the seeds, so the
default run is held to the best converged quality we know. Prints the
per-seed table, the median time of the default runs and the ratio of their
mean variance to the reference; with --target-seconds, a PASS/FAIL line for
"median time <= target and mean ratio <= 1 + --tolerance".

Converged references are kept in --work-dir and reused on later runs.

  /usr/bin/python3 bench/time_to_quality.py --n 4096 --seeds 8 --target-seconds 1.7
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import time


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}{r.stderr}")
    return r.stdout


def optimize(args, seed, path, extra):
    cmd = [args.cli, "optimize", "--n", str(args.n), "--dir", f"{args.theta:g}", "--seed",
           str(seed), "--engine", args.engine, "--threads", str(args.threads), "--out", path] + extra
    out = run(cmd)
    secs = float(re.search(r"^time\s+([\d.]+) s", out, re.M).group(1))
    iters = int(re.search(r"^iterations\s+(\d+)", out, re.M).group(1))
    return secs, iters


def variance(args, path):
    out = run([args.cli, "evaluate", path, "--normal", f"{args.theta:g}"])
    return float(re.search(r"^variance\s+(\S+)", out, re.M).group(1))


def converged(args, seed, label, extra):
    """A fully converged set (cached): (variance, iterations)."""
    path = os.path.join(args.work_dir, f"converged_{label}_n{args.n}_t{args.theta:g}_s{seed}.txt")
    meta = path + ".iterations"
    if not os.path.exists(path) or not os.path.exists(meta):
        _, iters = optimize(args, seed, path, ["--max-iterations", "1000000"] + extra)
        with open(meta, "w") as f:
            f.write(f"{iters}\n")
    with open(meta) as f:
        iters = int(f.read())
    return variance(args, path), iters


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/cli/alignset")
    ap.add_argument("--n", type=int, default=4096)
    ap.add_argument("--theta", type=float, default=30.0)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--engine", default="fast")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3,
                    help="timed runs per seed (the time is their median)")
    ap.add_argument("--target-seconds", type=float, default=0.0)
    ap.add_argument("--tolerance", type=float, default=0.10)
    ap.add_argument("--work-dir", default="build/time_to_quality")
    args = ap.parse_args()
    os.makedirs(args.work_dir, exist_ok=True)

    print(f"# N={args.n} θ={args.theta:g} engine={args.engine} threads={args.threads} "
          f"seeds 1..{args.seeds}  ({time.strftime('%Y-%m-%d')}, load {os.getloadavg()[0]:.2f})")
    print(f"{'seed':>4} {'conv c=4N':>11} {'(iters)':>8} {'conv c=N':>11} {'(iters)':>8}"
          f" {'default':>11} {'iters':>6} {'time s':>7}")
    rows = []
    for seed in range(1, args.seeds + 1):
        c4, i4 = converged(args, seed, "c4n", [])
        c1, i1 = converged(args, seed, "c1n", ["--sw-weight", str(args.n)])
        path = os.path.join(args.work_dir, f"default_n{args.n}_t{args.theta:g}_s{seed}.txt")
        times = []
        for _ in range(args.repeats):
            secs, iters = optimize(args, seed, path, [])
            times.append(secs)
        v = variance(args, path)
        t = statistics.median(times)
        rows.append((c4, c1, v, t))
        print(f"{seed:>4} {c4:>11.4e} {i4:>8} {c1:>11.4e} {i1:>8} {v:>11.4e} {iters:>6} {t:>7.2f}",
              flush=True)

    mean = lambda xs: sum(xs) / len(xs)
    ref4 = mean([r[0] for r in rows])
    ref1 = mean([r[1] for r in rows])
    reference = min(ref4, ref1)
    got = mean([r[2] for r in rows])
    worst = max(r[2] for r in rows) / reference
    t_med = statistics.median([r[3] for r in rows])
    ratio = got / reference
    print(f"converged mean: c=4N {ref4:.4e}, c=N {ref1:.4e}; reference (lower) {reference:.4e}")
    print(f"default runs: mean variance {got:.4e} = {ratio:.3f} x reference "
          f"(worst seed {worst:.3f} x); median time {t_med:.2f} s")
    if args.target_seconds > 0:
        ok = t_med <= args.target_seconds and ratio <= 1.0 + args.tolerance
        print(f"check (median time <= {args.target_seconds:g} s and mean variance within "
              f"{args.tolerance:.0%} of converged): {'PASS' if ok else 'FAIL'}")


if __name__ == "__main__":
    main()
