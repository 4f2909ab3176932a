#!/usr/bin/env python3
"""Where an estimated-direction sampler loses, pixel by pixel: the edge
pixels of a seeds.sh run split by what the geometry says they are (one
straight edge, a corner, ...; one or two directions) and by what the
pre-pass made of them (no direction, one, two), each group's squared error
for the sampler, for the same sampler with the geometry's direction (its
`-exact` row, the same N) and for the best other point sampler at the same
total samples per pixel (the counted run).

  SEEDS="1 2 3" N=256 PREPASS=nedges64 RAW=build/render-split256 \
    SAMPLERS=owen-sobol,pmj02bn,rank1-lattice,screen-space-rank1,aligned-lattice+reuse,aligned-lattice-exact \
    bash bench/render/seeds.sh
  pixel_split.py --raw build/render-split256 --seeds "1 2 3" --n 256 --pre 64 --out FILE.md
      [--sampler aligned-lattice+reuse --exact aligned-lattice-exact]

Reads the images render_bench writes (DIR/seedS/images, DIR/seedS-counted/
images): the reference, the pixel classes, shapes and direction kinds, and
each sampler's image. Each group's row gives its share of the sampler's edge
error, the sampler's MSE over the exact one's (what the estimate costs
there) and the best baseline's MSE over the sampler's (above 1: the sampler
wins), the groups' figures summed over seeds before the ratio.
"""
import argparse
import os
import sys

import numpy as np

SHAPES = ["none", "straight", "parallel", "curved", "corner"]  # render/pixel_shape.h
KINDS = ["none", "one", "two"]                                 # PixelDirection::Kind
EDGE = 0                                                       # PixelClass::kEdge
BASELINES = ["owen-sobol", "pmj02bn", "rank1-lattice", "screen-space-rank1"]


def load(path):
    return np.load(path).ravel()


def scene_data(raw, seed, scene, n, total, sampler, exact):
    d = os.path.join(raw, f"seed{seed}", "images")
    c = os.path.join(raw, f"seed{seed}-counted", "images")
    img = lambda folder, name, m: os.path.join(folder, f"{scene}_{name}_n{m}.npy")
    ref = load(os.path.join(d, f"{scene}_reference.npy"))
    out = {
        "edge": load(os.path.join(d, f"{scene}_classes.npy")) == EDGE,
        "shape": load(os.path.join(d, f"{scene}_shapes.npy")).astype(int),
        "est": load(os.path.join(d, f"{scene}_kind_estimated.npy")).astype(int),
        "geo": load(os.path.join(d, f"{scene}_kind_exact.npy")).astype(int),
        "sampler": (load(img(d, sampler, n)) - ref) ** 2,
        "exact": (load(img(d, exact, n)) - ref) ** 2,
    }
    # The best baseline of this seed and scene: lowest edge MSE at the total.
    best, best_mse = None, None
    for b in BASELINES:
        p = img(c, b, total)
        if not os.path.exists(p):
            continue
        e = (load(p) - ref) ** 2
        mse = e[out["edge"]].mean()
        if best_mse is None or mse < best_mse:
            best, best_mse = (b, e), mse
    if best is None:
        sys.exit(f"pixel_split: no baseline image at N = {total} in {c}")
    out["best_name"], out["best"] = best
    return out


def groups():
    yield "all edge pixels", lambda s: s["edge"]
    for shape in ["straight", "corner", "curved", "parallel"]:
        for geo in [1, 2]:
            for est in [0, 1, 2]:
                label = f"{shape}, {KINDS[geo]} by the geometry, {KINDS[est]} estimated"
                yield label, (lambda s, shape=shape, geo=geo, est=est:
                              s["edge"] & (s["shape"] == SHAPES.index(shape)) & (s["geo"] == geo) &
                              (s["est"] == est))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raw", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--n", type=int, required=True)
    ap.add_argument("--pre", type=int, required=True, help="pre-pass evaluations per pixel")
    ap.add_argument("--sampler", default="aligned-lattice+reuse")
    ap.add_argument("--exact", default="aligned-lattice-exact")
    ap.add_argument("--out", required=True)
    ap.add_argument("--min-pixels", type=int, default=20)
    a = ap.parse_args()
    seeds = a.seeds.split()
    total = a.n + a.pre
    lines = [f"# Where `{a.sampler}` loses at N = {a.n} + {a.pre}, by pixel type and estimate", "",
             f"Written by `bench/render/pixel_split.py` from a `bench/render/seeds.sh` run (scene seeds "
             f"{', '.join(seeds)}; raw images in `{a.raw}`). Edge pixels grouped by their shape and number of "
             f"directions from the geometry and by the pre-pass's estimate; per group, summed over the seeds: "
             f"its share of `{a.sampler}`'s edge error, what the estimate costs there (`{a.sampler}` / "
             f"`{a.exact}`, both at N = {a.n}, the exact one without a pre-pass) and the best other point "
             f"sampler at the same total {total} over `{a.sampler}` (above 1: `{a.sampler}` wins; the best "
             f"baseline is chosen per seed and scene on all edge pixels). Groups under {a.min_pixels} pixels "
             f"over all seeds are left out.", ""]
    for scene in ["antialias", "shadow"]:
        data = [scene_data(a.raw, s, scene, a.n, total, a.sampler, a.exact) for s in seeds]
        names = ", ".join(f"{s}: {d['best_name']}" for s, d in zip(seeds, data))
        lines += [f"## {scene} (best baseline per seed: {names})", "",
                  "| pixels | count | share of the error | estimate's cost (sampler / exact) | "
                  "best baseline / sampler |", "|---|---:|---:|---:|---:|"]
        total_err = sum(d["sampler"][d["edge"]].sum() for d in data)
        for label, select in groups():
            masks = [select(d) for d in data]
            count = sum(int(m.sum()) for m in masks)
            if count < a.min_pixels:
                continue
            err = sum(d["sampler"][m].sum() for d, m in zip(data, masks))
            ex = sum(d["exact"][m].sum() for d, m in zip(data, masks))
            best = sum(d["best"][m].sum() for d, m in zip(data, masks))
            lines.append(f"| {label} | {count} | {err / total_err:.2f} | {err / ex:.2f} | {best / err:.2f} |")
        lines.append("")
    with open(a.out, "w") as f:
        f.write("\n".join(lines))
    print(f"pixel_split: wrote {a.out}")


if __name__ == "__main__":
    main()
