#!/usr/bin/python3
"""Where a soaked server's memory is, over time: one panel per soak run.

    /usr/bin/python3 bench/soak_memory_plot.py --out FIG.png LABEL=SAMPLES.tsv [LABEL=SAMPLES.tsv ...]

SAMPLES.tsv is what `alignset_soak --samples` writes (every 2 s: resident,
anonymous and file-backed resident memory from /proc, malloc's bytes in use
and kept free, the set LRU's and SQLite's bytes from GetMetrics). The restart
after the SIGKILL is marked; the warm-up the soak leaves out (the first 20% of
the second server's life) is shaded.
"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SERIES = [
    ("rss_mb", "resident (VmRSS)", "black"),
    ("anon_mb", "resident anonymous", "tab:red"),
    ("file_mb", "resident files", "tab:gray"),
    ("heap_mb", "allocated (in use)", "tab:blue"),
    ("free_mb", "allocator kept, not in use", "tab:orange"),
    ("lru_mb", "set LRU", "tab:green"),
    ("sqlite_mb", "SQLite", "tab:purple"),
]


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f, delimiter="\t"))
    return {k: [float(r[k]) if k in r else -1.0 for r in rows] for k in ["t_s", "life"] + [s[0] for s in SERIES]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("runs", nargs="+", help="LABEL=SAMPLES.tsv")
    a = ap.parse_args()
    fig, axes = plt.subplots(len(a.runs), 1, figsize=(10, 3.6 * len(a.runs)), sharex=True, squeeze=False)
    for ax, run in zip(axes[:, 0], a.runs):
        label, path = run.split("=", 1)
        d = read(path)
        t = [x / 60.0 for x in d["t_s"]]
        restart = next((t[i] for i, life in enumerate(d["life"]) if life == 2), None)
        if restart is not None:
            ax.axvline(restart, color="k", ls=":", lw=1)
            warm = restart + 0.2 * (t[-1] - restart)
            ax.axvspan(restart, warm, color="0.9")
        for key, name, color in SERIES:
            pts = [(x, y) for x, y in zip(t, d[key]) if y >= 0]
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], color=color, lw=0.8, label=name)
        ax.set_title(label, fontsize=10)
        ax.set_ylabel("MB")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7, ncol=4, loc="lower right")
    axes[-1, 0].set_xlabel("minutes (dotted: the restart after the SIGKILL; shaded: warm-up, left out)")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()
