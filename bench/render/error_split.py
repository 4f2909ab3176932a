#!/usr/bin/env python3
"""Where the rendered edge error of `aligned` comes from: by pixel type and by
cause, over scene seeds (issue 26).

  error_split.py --raw DIR --seeds "1 2 3" --n 256,1024,4096 --out FILE.md [--figure FILE.png]

DIR/seedS/ is a render_bench output (render_errors.csv with the edge_<type>
columns, images/<scene>_shapes.npy) of a run with the samplers below. The
pixel types come from the scene's geometry (render/pixel_shape.h):
straight (one straight edge), parallel (two or more parallel edges: a thin
feature), curved (directions within 15 degrees: a polygonized curve), corner
(a corner or crossing).

The causes are a ladder of samplers on the same pixels, each removing one:
  aligned                the shipped recipe: estimated direction, served grid,
                         optimized set, per-pixel shift
  aligned-exact          the geometry's direction   -> the estimate's cost
  aligned-exact-1dir     one direction only         -> what two-direction sets give
  aligned-exact-noshift  no per-pixel shift         -> the shift's cost
  aligned-lattice-exact  an aligned lattice (no sqrt(N) strip floor)
                                                    -> the optimized set's floor
"""
import argparse
import csv
import os
import sys

import numpy as np

from ratios import fmt, gmean

TYPES = ["straight", "parallel", "curved", "corner"]
SHAPE_CODE = {"straight": 1, "parallel": 2, "curved": 3, "corner": 4}  # render/pixel_shape.h
LADDER = ["owen-sobol", "aligned", "aligned-exact", "aligned-exact-1dir", "aligned-exact-noshift",
          "aligned-lattice", "aligned-lattice-exact"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raw", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--n", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--figure")
    a = ap.parse_args()
    seeds = a.seeds.split()
    ns = [int(n) for n in a.n.split(",")]
    mse = {}     # (seed, scene, sampler, n, subset) -> mse
    counts = {}  # (seed, scene, type) -> pixels
    for s in seeds:
        d = os.path.join(a.raw, "seed" + s)
        with open(os.path.join(d, "render_errors.csv")) as f:
            for r in csv.DictReader(f):
                for k, v in r.items():
                    if k.startswith("mse_edge"):
                        mse[(s, r["scene"], r["sampler"], int(r["n"]), k[4:])] = float(v) if v else float("nan")
        for scene in ("antialias", "shadow"):
            path = os.path.join(d, "images", scene + "_shapes.npy")
            if not os.path.exists(path):
                continue
            shapes = np.load(path)
            for t in TYPES:
                counts[(s, scene, t)] = int((shapes == SHAPE_CODE[t]).sum())
    scenes = sorted({k[1] for k in mse})
    out = ["# Where the edge error goes: by pixel type and by cause\n",
           "Written by `bench/render/error_split.py` from render_bench runs over scene seeds %s "
           "(`bash bench/render/split.sh`). Pixel types from the geometry "
           "(render/pixel_shape.h). Every ratio is a geometric mean over the seeds. "
           "*share* is the type's part of `aligned`'s summed squared edge error; the OS/… columns "
           "are Owen-Sobol's MSE over the sampler's on that type (above 1: the sampler wins); "
           "the cause columns are MSE ratios of neighbouring rungs of the ladder "
           "(above 1: that cause costs this factor).\n" % ", ".join(seeds)]
    fig_data = {}
    for scene in scenes:
        for n in ns:
            out.append("\n## %s, N = %d\n" % (scene, n))
            out.append("| type | pixels (per seed) | share of aligned's error | OS / aligned | OS / aligned-exact "
                       "| OS / aligned-lattice-exact | direction estimate (aligned / exact) "
                       "| one direction only (1dir / exact) | per-pixel shift (exact / noshift) "
                       "| optimized set's floor (exact / lattice-exact) |")
            out.append("|---|---|---|---|---|---|---|---|---|---|")
            total = {s: sum(mse.get((s, scene, "aligned", n, "edge_" + t), 0.0) * counts.get((s, scene, t), 0)
                            for t in TYPES) for s in seeds}
            for t in TYPES + ["all"]:
                sub = "edge" if t == "all" else "edge_" + t

                def m(sampler, s):
                    return mse.get((s, scene, sampler, n, sub), float("nan"))

                def ratio(num, den):
                    return gmean([m(num, s) / m(den, s) for s in seeds])

                if t == "all":
                    pixels = "%d" % round(sum(sum(counts.get((s, scene, u), 0) for u in TYPES) for s in seeds) / len(seeds))
                    share = "1"
                else:
                    pixels = ", ".join(str(counts.get((s, scene, t), 0)) for s in seeds)
                    share = fmt(gmean([m("aligned", s) * counts.get((s, scene, t), 0) / total[s]
                                       for s in seeds if total[s] > 0]))
                row = [t, pixels, share, fmt(ratio("owen-sobol", "aligned")), fmt(ratio("owen-sobol", "aligned-exact")),
                       fmt(ratio("owen-sobol", "aligned-lattice-exact")), fmt(ratio("aligned", "aligned-exact")),
                       fmt(ratio("aligned-exact-1dir", "aligned-exact")),
                       fmt(ratio("aligned-exact", "aligned-exact-noshift")),
                       fmt(ratio("aligned-exact", "aligned-lattice-exact"))]
                out.append("| " + " | ".join(row) + " |")
                fig_data[(scene, n, t)] = {smp: ratio("owen-sobol", smp) for smp in LADDER[1:]}
    text = "\n".join(out) + "\n"
    with open(a.out, "w") as f:
        f.write(text)
    sys.stdout.write(text)
    if a.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        samplers = ["aligned", "aligned-exact", "aligned-lattice", "aligned-lattice-exact"]
        fig, axes = plt.subplots(len(scenes), len(ns), figsize=(4.2 * len(ns), 3.4 * len(scenes)),
                                 squeeze=False, sharey=True)
        for i, scene in enumerate(scenes):
            for j, n in enumerate(ns):
                ax = axes[i][j]
                width = 0.8 / len(samplers)
                for k, smp in enumerate(samplers):
                    ys = [fig_data.get((scene, n, t), {}).get(smp, float("nan")) for t in TYPES + ["all"]]
                    xs = [x + (k - len(samplers) / 2 + 0.5) * width for x in range(len(TYPES) + 1)]
                    # Bars from 1 (Owen-Sobol), up where the sampler wins, down where it loses.
                    ax.bar(xs, [y - 1.0 for y in ys], width, bottom=1.0, label=smp)
                ax.axhline(1.0, color="k", lw=0.8)
                ax.set_yscale("log")
                ax.set_ylim(0.3, 10.0)
                ax.set_xticks(range(len(TYPES) + 1))
                ax.set_xticklabels(TYPES + ["all"], fontsize=8)
                ax.set_title("%s, N = %d" % (scene, n), fontsize=9)
                if j == 0:
                    ax.set_ylabel("Owen-Sobol MSE / sampler MSE")
        axes[0][0].legend(fontsize=7)
        fig.suptitle("Edge pixels by type: gain over Owen-Sobol (geometric mean over seeds %s)" % ", ".join(seeds),
                     fontsize=10)
        fig.tight_layout()
        fig.savefig(a.figure, dpi=110)


if __name__ == "__main__":
    main()
