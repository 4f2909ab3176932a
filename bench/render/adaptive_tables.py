#!/usr/bin/env python3
"""Tables and a figure from bench/render/adaptive_render's TSV files: for each
scene seed, the mean samples an edge pixel spent against the edge pixels' MSE,
one curve per sampler (a point per threshold tau). At each target error (what
the lattice sequence reaches at tau = 1e-2, 3e-3, 1e-3 and 3e-4), the samples
every other sampler needs for the same edge MSE, interpolated log-log along
its own curve: the ratio other / lattice-sequence (above 1: the sequence
spends fewer samples). '>' when a sampler never gets that low.

  adaptive_tables.py bench/results/adaptive/antialias.tsv [more.tsv] --out bench/results/adaptive/summary.md
"""
import argparse
import math
import os
import sys
from collections import defaultdict

import numpy as np

SAMPLERS = ["lattice-sequence", "lattice", "owen-sobol", "pmj02bn", "lattice-sequence-no-prepass"]
TARGET_TAUS = [1e-2, 3e-3, 1e-3, 3e-4]


def read(paths):
    curves = defaultdict(list)  # (scene, seed, sampler) -> [(tau, samples, mse)]
    for path in paths:
        with open(path) as fh:
            head = fh.readline().rstrip("\n").split("\t")
            for line in fh:
                r = dict(zip(head, line.rstrip("\n").split("\t")))
                curves[(r["scene"], int(r["seed"]), r["sampler"])].append(
                    (float(r["tau"]), float(r["edge_samples"]), float(r["edge_mse"])))
    return curves


def samples_for(curve, mse):
    """Samples needed for `mse` along a curve: the fewest samples of any tau
    reaching it, interpolated log-log between the neighbouring points."""
    pts = sorted((s, e) for _, s, e in curve)
    best = None
    for (s0, e0), (s1, e1) in zip(pts, pts[1:]):
        lo, hi = min(e0, e1), max(e0, e1)
        if lo <= mse <= hi and e0 != e1:
            t = (math.log(mse) - math.log(e0)) / (math.log(e1) - math.log(e0))
            s = math.exp(math.log(s0) + t * (math.log(s1) - math.log(s0)))
            best = s if best is None else min(best, s)
    if best is None and pts and pts[0][1] <= mse:
        best = pts[0][0]
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tsv", nargs="+")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    curves = read(a.tsv)
    scenes = sorted({(k[0], k[1]) for k in curves})
    lines = ["# Adaptive sampling: samples an edge pixel spends for the same edge error",
             "", "(bench/render/adaptive_render, bench/render/adaptive_tables.py.) Each cell: samples of that sampler "
             "/ samples of the lattice sequence for the edge MSE the sequence reaches at that tau (every sample "
             "counted: pre-pass and, for the fixed-size lattice, every stage's set).", ""]
    lines.append("| scene | seed | tau | edge MSE | seq samples | " + " | ".join(s + " / seq" for s in SAMPLERS[1:]) + " |")
    lines.append("|---|---|---|---|---|" + "---|" * (len(SAMPLERS) - 1))
    ratios = defaultdict(list)
    for scene, seed in scenes:
        seq = curves[(scene, seed, "lattice-sequence")]
        for tau in TARGET_TAUS:
            row = min(seq, key=lambda r: abs(math.log(r[0] / tau)))
            mse, n_seq = row[2], row[1]
            cells = []
            for s in SAMPLERS[1:]:
                n = samples_for(curves[(scene, seed, s)], mse)
                if n is None:
                    cells.append("> %.0f" % max(x[1] for x in curves[(scene, seed, s)]))
                else:
                    cells.append("%.2f" % (n / n_seq))
                    ratios[(scene, tau, s)].append(n / n_seq)
            lines.append("| %s | %d | %.0e | %.2e | %.0f | %s |" % (scene, seed, tau, mse, n_seq, " | ".join(cells)))
    lines += ["", "Geometric mean over the seeds (seeds where a sampler never reached the error left out, "
              "counted in brackets):", ""]
    lines.append("| scene | tau | " + " | ".join(s + " / seq" for s in SAMPLERS[1:]) + " |")
    lines.append("|---|---|" + "---|" * (len(SAMPLERS) - 1))
    for scene in sorted({s for s, _ in scenes}):
        seeds = [sd for sc, sd in scenes if sc == scene]
        for tau in TARGET_TAUS:
            cells = []
            for s in SAMPLERS[1:]:
                r = ratios[(scene, tau, s)]
                miss = len(seeds) - len(r)
                cells.append(("%.2f" % math.exp(np.mean(np.log(r))) if r else "-") + (" [%d never]" % miss if miss else ""))
            lines.append("| %s | %.0e | %s |" % (scene, tau, " | ".join(cells)))
    text = "\n".join(lines) + "\n"
    with open(a.out, "w") as fh:
        fh.write(text)
    sys.stdout.write(text)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        names = sorted({sc for sc, _ in scenes})
        cols = max(sum(1 for sc, _ in scenes if sc == name) for name in names)
        fig, axes = plt.subplots(len(names), cols, figsize=(3.4 * cols, 3.0 * len(names)), squeeze=False)
        slots = []
        for r, name in enumerate(names):
            slots += [(axes[r][c], (name, sd)) for c, sd in enumerate(sd for sc, sd in scenes if sc == name)]
        for ax, (scene, seed) in slots:
            for s in SAMPLERS:
                c = sorted(curves[(scene, seed, s)], key=lambda r: r[1])
                ax.loglog([r[1] for r in c], [r[2] for r in c], marker=".", label=s)
            ax.set_title("%s seed %d" % (scene, seed))
            ax.set_xlabel("samples per edge pixel")
            ax.set_ylabel("edge MSE")
        axes[0][0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.splitext(a.out)[0] + ".png", dpi=90)
    except ImportError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
