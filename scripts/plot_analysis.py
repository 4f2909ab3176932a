#!/usr/bin/python3
"""The one plotting path of alignset's analysis commands (Debian's matplotlib).

  /usr/bin/python3 scripts/plot_analysis.py DATA.json --out FIG.png

DATA.json is what `alignset analyze --json` or `alignset convergence --json`
prints ("kind": "spectrum" or "convergence"), or what `alignset joint --png`
hands it ("kind": "joint": a pixel's 2-D projections); `--png` on those
commands runs this script itself. A list of spectrum documents (a JSON array)
draws one row of spectra side by side, which bench/figures uses for its
spectrum panel.
"""
import argparse
import json
import math
import sys

import numpy as np


def spectrum_axes(fig, grid, row, doc, compact=False):
    import matplotlib.pyplot as plt  # noqa: F401
    from matplotlib.colors import LogNorm

    m = doc["max_frequency"]
    power = np.array([[np.nan if v is None else v for v in r] for r in doc["power"]])
    ax = fig.add_subplot(grid[row, 0])
    im = ax.imshow(power.T, origin="lower", extent=[-m - .5, m + .5, -m - .5, m + .5],
                   norm=LogNorm(vmin=1e-3, vmax=10), cmap="magma", interpolation="nearest")
    title = doc.get("title") or ", ".join(doc.get("files", []))[:60]
    ax.set_title(f"{title}\nN = {doc['n']}, {doc['sets']} set(s)", fontsize=9)
    ax.set_xlabel("a")
    ax.set_ylabel("b")
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04)

    ax = fig.add_subplot(grid[row, 1])
    radial = doc["radial"]
    ax.semilogy(range(1, len(radial)), radial[1:], color="k")
    ax.axhline(1.0, color="gray", lw=0.8, ls="--")
    ax.set_xlabel("|v|")
    ax.set_title("radial profile", fontsize=9)

    ax = fig.add_subplot(grid[row, 2])
    for d in doc["directional"]:
        # null: no integer frequency lies on the line at that |v|.
        pts = [(t, max(x, 1e-6)) for t, x in enumerate(d["power"]) if t > 0 and x is not None]
        ax.semilogy([t for t, _ in pts], [x for _, x in pts], lw=0.9, marker=".", ms=2,
                    label=f"{d['deg']:g}°")
    ax.axhline(1.0, color="gray", lw=0.8, ls="--")
    ax.set_xlabel("|v| along the direction")
    ax.set_title("directional profiles", fontsize=9)
    ax.legend(fontsize=7)

    ax = fig.add_subplot(grid[row, 3], projection="polar")
    p = np.array(doc["angular"]["power"])
    bins = len(p)
    theta = (np.arange(bins) + 0.5) * math.pi / bins
    # P(v) = P(-v): the half turn is drawn twice.
    ax.plot(np.concatenate([theta, theta + math.pi, theta[:1]]),
            np.concatenate([p, p, p[:1]]), color="C3", lw=1)
    ax.set_title(f"angular energy, |v| >= {doc['angular']['r_min']:g}", fontsize=9)
    ax.tick_params(labelsize=7)


def plot_spectra(docs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(17, 3.9 * len(docs)))
    grid = fig.add_gridspec(len(docs), 4, width_ratios=[1.15, 1, 1, 0.9])
    for row, doc in enumerate(docs):
        spectrum_axes(fig, grid, row, doc)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def plot_convergence(doc, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    integrands = []
    for s in doc["series"]:
        if s["integrand"] not in integrands:
            integrands.append(s["integrand"])
    cols = min(3, len(integrands))
    rows = math.ceil(len(integrands) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.2 * rows), squeeze=False)
    for i, name in enumerate(integrands):
        ax = axes[i // cols][i % cols]
        for s in doc["series"]:
            if s["integrand"] != name:
                continue
            n = np.array(s["n"], float)
            v = np.array([np.nan if x is None else x for x in s["variance"]], float)
            e = np.array([0 if x is None else x for x in s["std_error"]], float)
            slope = s.get("slope")
            label = s["label"] + (f"  ({slope:+.2f})" if slope is not None else "")
            ls = "--" if s.get("homogenize") == "none" and "(no CP)" in s["label"] else "-"
            ax.errorbar(n, v, yerr=e, marker="o", ms=3, lw=1.2, ls=ls, capsize=2, label=label)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("N")
        ax.set_ylabel("variance")
        ax.set_title(name, fontsize=10)
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.legend(fontsize=7)
    for j in range(len(integrands), rows * cols):
        axes[j // cols][j % cols].axis("off")
    if doc.get("title"):
        fig.suptitle(doc["title"])
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def plot_joint(doc, out):
    """A joint lattice's pixel (alignset joint --png): every 2-D projection
    of its first dimensions, each titled with the pair's spacing (the
    shortest dual vector against the hexagonal lattice's)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = [np.array(c, float) for c in doc["columns"]]
    k = len(cols)
    if k < 2:
        sys.exit("plot_analysis: a joint document needs two dimensions or more to draw a pair")
    spacing = {(int(a), int(b)): s for a, b, s in doc["spacing"]}
    labels = doc.get("labels") or [f"d{d}" for d in range(k)]
    fig, axes = plt.subplots(k - 1, k - 1, figsize=(2.6 * (k - 1), 2.6 * (k - 1)), squeeze=False)
    for b in range(1, k):
        for a in range(k - 1):
            ax = axes[b - 1][a]
            if a >= b:
                ax.axis("off")
                continue
            ax.scatter(cols[a], cols[b], s=max(0.5, 400 / len(cols[a])), lw=0)
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            s = spacing.get((a, b))
            ax.set_title(f"{labels[a]}, {labels[b]}" + (f": {s:.2f}" if s is not None else ""), fontsize=8)
    if doc.get("title"):
        fig.suptitle(doc["title"], fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("data")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    try:
        with open(args.data) as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_analysis: cannot read {args.data}: {e}")
    docs = doc if isinstance(doc, list) else [doc]
    kinds = {d.get("kind") for d in docs}
    try:
        if kinds == {"spectrum"}:
            plot_spectra(docs, args.out)
        elif kinds == {"convergence"} and len(docs) == 1:
            plot_convergence(docs[0], args.out)
        elif kinds == {"joint"} and len(docs) == 1:
            plot_joint(docs[0], args.out)
        else:
            sys.exit(f"plot_analysis: {args.data}: expected one convergence or joint document or "
                     f"spectrum documents, got {sorted(map(str, kinds))}")
    except OSError as e:
        sys.exit(f"plot_analysis: cannot write {args.out}: {e}")


if __name__ == "__main__":
    main()
