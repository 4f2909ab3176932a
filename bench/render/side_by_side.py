#!/usr/bin/env python3
"""One scene, side by side: the exact reference and each sampler's image at one N,
with its error map below (|image - reference|, one logarithmic colour scale for
all) and its edge-pixel MSE in the title. Reads render_bench's images/ folders.

  side_by_side.py --images DIR/images --scene shadow --n 1024 \
      --samplers owen-sobol,rank1-lattice,aligned,aligned-lattice --out FIG.png

Every sample counted: a sampler written name@N is read at that N instead (the
baselines at N + the pre-pass), and --images may list several folders, comma
separated, searched in order (seeds.sh keeps the baselines at N + P in
seedS-counted/images).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

EDGE = 0  # render/pixel_integrand.h PixelClass::kEdge


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--images", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--n", type=int, required=True)
    ap.add_argument("--samplers", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    folders = a.images.split(",")

    def load(name):
        for d in folders:
            path = os.path.join(d, name)
            if os.path.exists(path):
                return np.load(path)
        raise SystemExit("side_by_side.py: %s is in none of %s" % (name, folders))

    ref = load(a.scene + "_reference.npy")
    classes = load(a.scene + "_classes.npy")
    names, imgs = [], []
    for entry in a.samplers.split(","):
        sampler, _, n = entry.partition("@")
        n = int(n) if n else a.n
        imgs.append(load("%s_%s_n%d.npy" % (a.scene, sampler, n)))
        names.append(sampler if n == a.n else "%s at %d" % (sampler, n))
    errs = [np.abs(i - ref) for i in imgs]
    hi = max(e.max() for e in errs)
    lo = hi * 1e-5
    fig, ax = plt.subplots(2, len(names) + 1, figsize=(2.6 * (len(names) + 1), 5.6))
    vmin, vmax = ref.min(), ref.max()
    ax[0, 0].imshow(ref, cmap="gray", vmin=vmin, vmax=vmax)
    ax[0, 0].set_title("reference (exact)", fontsize=9)
    ax[1, 0].imshow(classes == EDGE, cmap="gray")
    ax[1, 0].set_title("edge pixels", fontsize=9)
    for k, (name, img, err) in enumerate(zip(names, imgs, errs)):
        mse = float(np.mean(((img - ref)[classes == EDGE]) ** 2))
        ax[0, k + 1].imshow(img, cmap="gray", vmin=vmin, vmax=vmax)
        ax[0, k + 1].set_title("%s\nedge MSE %.2e" % (name, mse), fontsize=9)
        im = ax[1, k + 1].imshow(np.log10(np.maximum(err, lo)), cmap="magma",
                                 vmin=np.log10(lo), vmax=np.log10(hi))
        ax[1, k + 1].set_title("log10 |error|", fontsize=9)
    for x in ax.flat:
        x.set_xticks([])
        x.set_yticks([])
    fig.colorbar(im, ax=ax[1, :].tolist(), shrink=0.8)
    fig.suptitle(a.title or "%s, N = %d" % (a.scene, a.n), fontsize=11)
    fig.savefig(a.out, dpi=110, bbox_inches="tight")


if __name__ == "__main__":
    main()
