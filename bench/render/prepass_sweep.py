#!/usr/bin/env python3
"""The table of bench/render/prepass_sweep.sh: for each scene, pre-pass size M
and lattice window W, Owen-Sobol's and the best baseline's edge MSE at N + M
over aligned-lattice+reuse's at N (geometric mean over the seeds, range).

  prepass_sweep.py --raw DIR --n 256 --seeds "1 2 3" --ms "32 64 128" \
      --windows "0.5 1 2 3" --out FILE.md
"""
import argparse
import csv
import os

from ratios import ratio_text

BASELINES = ("owen-sobol", "pmj02bn", "rank1-lattice", "screen-space-rank1")


def edge_mse(path, scene):
    with open(path) as f:
        return {r["sampler"]: float(r["mse_edge"]) for r in csv.DictReader(f) if r["scene"] == scene}


def main():
    ap = argparse.ArgumentParser()
    for k in ("raw", "n", "seeds", "ms", "windows", "out"):
        ap.add_argument("--" + k, required=True)
    ap.add_argument("--kind", default="edges")
    a = ap.parse_args()
    seeds, ms, windows = a.seeds.split(), a.ms.split(), a.windows.split()
    out = ["# Pre-pass size and lattice window at N = %s, every sample counted\n" % a.n,
           "Written by `bench/render/prepass_sweep.py` from `bash bench/render/prepass_sweep.sh` "
           "(scene seeds %s). `aligned-lattice+reuse` with the pre-pass %sM and lattices chosen "
           "for ±W degrees around the estimated θ, against Owen-Sobol and the best of Owen-Sobol, "
           "pmj02bn, the rank-1 lattice and screen-space rank-1, each rendered at N + M; edge "
           "pixels; the baseline's MSE over the lattice's (above 1: the lattice wins), geometric "
           "mean over seeds and range.\n" % (" ".join(seeds), a.kind)]
    for scene in ("antialias", "shadow"):
        out.append("\n## %s\n" % scene)
        out.append("| M | total | W | Owen-Sobol / lattice | best baseline / lattice |")
        out.append("|---:|---:|---:|---|---|")
        for m in ms:
            for w in windows:
                r_os, r_best = [], []
                for s in seeds:
                    lat = edge_mse(os.path.join(a.raw, "s%s-m%s-w%s" % (s, m, w), "render_errors.csv"),
                                   scene)["aligned-lattice+reuse"]
                    base = edge_mse(os.path.join(a.raw, "s%s-m%s-counted" % (s, m), "render_errors.csv"),
                                    scene)
                    r_os.append(base["owen-sobol"] / lat)
                    r_best.append(min(base[b] for b in BASELINES) / lat)
                out.append("| %s | %d | %s | %s | %s |" % (m, int(a.n) + int(m), w, ratio_text(r_os),
                                                           ratio_text(r_best)))
    with open(a.out, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
