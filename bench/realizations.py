#!/usr/bin/python3
"""Quality of every realization (issue 15): is realization r as good as realization 0?

Starts alignset-server on a fresh cache (default optimizer settings), fetches
realizations 0..R-1 of the key θ for each N with `alignset get -m R` (one batch
call), and measures each with `alignset evaluate`: the Cranley-Patterson-rotated
variance on 8 parallel step edges with normal θ (offsets -1/4..1/4, 4096 shifts
each; the measure of docs/results.md's quality table and of the CTest
Realizations.EveryRealizationMeetsTheQualityBarOfRealizationZero), beside
Owen-scrambled Sobol (mean of 4 scrambles, same shifts). Prints per N: realization 0, the mean / min / max over
all realizations, the worst realization against realization 0, and Owen-Sobol over
the mean.

  /usr/bin/python3 bench/realizations.py --n 256,1024,4096 --realizations 8 --theta 30
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}{r.stderr}")
    return r.stdout


def evaluate(cli, path, theta, shifts):
    """(this set's variance, Owen-Sobol's) from `alignset evaluate`."""
    out = run([cli, "evaluate", path, "--normal", f"{theta:g}", "--shifts", str(shifts)])
    for line in out.splitlines():
        if line.startswith("variance "):
            parts = line.split()
            return float(parts[1]), float(parts[2])
    sys.exit("no variance line in: " + out)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--n", default="256,1024,4096")
    ap.add_argument("--theta", type=float, default=30.0)
    ap.add_argument("--realizations", type=int, default=8)
    ap.add_argument("--shifts", type=int, default=4096)
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    cli = os.path.join(args.build, "client", "alignset")
    server_bin = os.path.join(args.build, "server", "alignset-server")
    work = tempfile.mkdtemp(prefix="alignset-realizations-")
    port_file = os.path.join(work, "port")
    server = subprocess.Popen([server_bin, "--listen", "127.0.0.1:0", "--port-file", port_file,
                               "--db", os.path.join(work, "cache.sqlite"), "--workers", "1",
                               "--threads-per-worker", str(args.threads), "--max-n", "65536",
                               "--log-level", "warn"])
    try:
        for _ in range(300):
            if os.path.exists(port_file) and os.path.getsize(port_file) > 0:
                break
            time.sleep(0.1)
        with open(port_file) as f:
            addr = "127.0.0.1:" + f.read().strip()
        print(f"theta {args.theta:g}, {args.realizations} realizations, 8 edges x {args.shifts} CP "
              f"shifts; server {addr}, 1 worker x {args.threads} threads")
        print(f"{'N':>6} {'r=0':>10} {'mean':>10} {'min':>10} {'max':>10} {'max/r0':>7} "
              f"{'sobol':>10} {'sobol/mean':>10} {'seconds':>8}")
        for n in [int(x) for x in args.n.split(",")]:
            sets = os.path.join(work, f"r_n{n}.npy")
            t0 = time.time()
            run([cli, "get", "-n", str(n), "--dir", f"{args.theta:g}", "-m", str(args.realizations),
                 "-q", "-o", sets, "--server", addr])
            seconds = time.time() - t0
            v = []
            for r in range(args.realizations):
                one = os.path.join(work, f"r{r}_n{n}.npy")  # a cache hit now
                run([cli, "get", "-n", str(n), "--dir", f"{args.theta:g}", "-r", str(r), "-q",
                     "-o", one, "--server", addr])
                mine, sobol = evaluate(cli, one, args.theta, args.shifts)
                v.append(mine)
            mean = statistics.mean(v)
            print(f"{n:>6} {v[0]:>10.3e} {mean:>10.3e} {min(v):>10.3e} {max(v):>10.3e} "
                  f"{max(v) / v[0]:>7.2f} {sobol:>10.3e} {sobol / mean:>10.2f} {seconds:>8.1f}",
                  flush=True)
            print("       per realization: " + " ".join(f"{x:.3e}" for x in v), flush=True)
    finally:
        server.terminate()
        server.wait()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
