#!/usr/bin/python3
"""Power spectrum (periodogram) of a point set as a PNG.

  /usr/bin/python3 scripts/plot_spectrum.py set.txt --out spectrum.png [--max-freq 128]

P(v) = |sum_j exp(-2 pi i v.s_j)|^2 / N at every integer frequency |a|, |b| <= max-freq,
shown on a log scale (white noise = 1, DC hidden), with the radially averaged spectrum
beside it. Reads UTK text ("x y" per line, '#' comments) or .npy (N x 2 float64).
"""
import argparse
import sys

import numpy as np


def load(path):
    if path.endswith(".npy"):
        return np.load(path)
    return np.loadtxt(path, comments="#", ndmin=2)


def periodogram(points, m):
    freqs = np.arange(-m, m + 1)
    power = np.zeros((2 * m + 1, 2 * m + 1))
    spectrum = np.zeros((2 * m + 1, 2 * m + 1), complex)
    # exp(-2 pi i (a x + b y)) = ex[a] * ey[b]: F is a matrix product, in chunks of points.
    for start in range(0, len(points), 4096):
        p = points[start:start + 4096]
        ex = np.exp(-2j * np.pi * np.outer(p[:, 0], freqs))
        ey = np.exp(-2j * np.pi * np.outer(p[:, 1], freqs))
        spectrum += ex.T @ ey
    power = np.abs(spectrum) ** 2 / len(points)
    power[m, m] = np.nan  # DC
    return freqs, power


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("points")
    ap.add_argument("--out", required=True)
    ap.add_argument("--max-freq", type=int, default=0, help="default: 2 sqrt(N), at most 256")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    try:
        pts = load(args.points)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_spectrum: cannot read {args.points}: {e}")
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) == 0:
        sys.exit(f"plot_spectrum: {args.points}: expected N x 2 points")
    m = args.max_freq or min(256, int(2 * np.sqrt(len(pts))))
    freqs, power = periodogram(pts, m)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 5), gridspec_kw={"width_ratios": [1.1, 1]})
    im = ax.imshow(power.T, origin="lower", extent=[-m - .5, m + .5, -m - .5, m + .5],
                   norm=LogNorm(vmin=1e-3, vmax=10), cmap="magma", interpolation="nearest")
    ax.set_xlabel("frequency a")
    ax.set_ylabel("frequency b")
    ax.set_title(args.title or f"periodogram, N = {len(pts)}")
    fig.colorbar(im, ax=ax, label="P(v)  (white noise = 1)")
    a, b = np.meshgrid(freqs, freqs, indexing="ij")
    r = np.rint(np.hypot(a, b)).astype(int)
    ok = ~np.isnan(power)
    radial = np.bincount(r[ok], weights=power[ok]) / np.maximum(np.bincount(r[ok]), 1)
    ax2.plot(np.arange(1, min(len(radial), m + 1)), radial[1:m + 1])
    ax2.axhline(1.0, color="gray", lw=0.8, ls="--")
    ax2.set_xlabel("|v|")
    ax2.set_ylabel("radially averaged P")
    ax2.set_title("radial average")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
