#!/usr/bin/env python3
"""Markdown tables of the constructions compared: the family bench's TSVs of
the aligned lattice and the optimized sets (both against Owen-Sobol, 16
scrambles, same shifts), and the independent evaluator's table
(bench/construction_eval.py).

  construction_tables.py [RESULTS_DIR]   (default bench/results)
"""
import csv
import os
import sys


def family(path):
    d = {}
    with open(path) as fh:
        for r in csv.DictReader(fh, delimiter="\t"):
            d[(float(r["theta"]), int(r["n"]), r["integrand"])] = float(r["ratio"])
    return d


def main(argv):
    res = argv[1] if len(argv) > 1 else "bench/results"
    lat = family(os.path.join(res, "family_lattice.tsv"))
    opt = family(os.path.join(res, "family_smooth_optimized.tsv"))
    thetas = sorted({k[0] for k in lat})
    ns = sorted({k[1] for k in lat})
    members = []
    for k in lat:
        if k[2] not in members:
            members.append(k[2])
    def pair_table(title, first, second, worse, need_second):
        # One table per N: each cell "first | second", ✗ where first is
        # above Owen-Sobol; without `second`'s value the cell is "–" when
        # need_second, else "first | –".
        out.extend(["### Variance / Owen-Sobol's on the family: " + title, ""])
        fmt = lambda x: ("%.3g" % x) if x >= 0.001 else ("%.0e" % x if x > 0 else "0")
        for n in sorted({k[1] for k in first}):
            out.append("N = %d" % n)
            out.append("")
            out.append("| member | " + " | ".join("θ = %g°" % t for t in thetas) + " |")
            out.append("|---|" + "---|" * len(thetas))
            for m in members:
                cells = []
                for t in thetas:
                    a, b = first.get((t, n, m)), second.get((t, n, m))
                    if a is None or (b is None and need_second):
                        cells.append("–")
                        continue
                    cells.append("%s \\| %s%s" % (fmt(a), fmt(b) if b is not None else "–", " ✗" if a > 1 else ""))
                out.append("| %s | %s |" % (m, " | ".join(cells)))
            out.append("")
        out.append("✗: the %s is worse than Owen-Sobol there." % worse)
        out.append("")

    out = []
    pair_table("aligned lattice | optimized set", lat, opt, "lattice", True)
    net_path = os.path.join(res, "family_net.tsv")
    if os.path.exists(net_path):
        pair_table("aligned net | aligned lattice", family(net_path), lat, "net", False)
    # construction_eval_tent.tsv: the tent-folded lattice measured in a run of
    # its own (CONSTRUCTIONS=tent-lattice); the evaluator is seeded, so its
    # Owen-Sobol rows are the main file's, and its rows join the table.
    rows = []
    for name in ("construction_eval.tsv", "construction_eval_tent.tsv"):
        ev = os.path.join(res, name)
        if os.path.exists(ev):
            rows += list(csv.DictReader(open(ev), delimiter="\t"))
    if rows:
        os_rows = {(r["N"], r["theta"]): r for r in rows if r["sampler"] == "owen-sobol"}
        # Grouped by N, then θ, in the main file's order.
        order = {}
        for r in rows:
            order.setdefault((r["N"], r["theta"]), len(order))
        rows.sort(key=lambda r: (int(r["N"]), order[(r["N"], r["theta"])]))
        out.append("### The independent evaluator: Owen-Sobol's variance / the construction's "
                   "(higher is better), edges 0 / 0.5 / 1 / 2 degrees off")
        out.append("")
        out.append("| N | θ | construction | edge 0° | 0.5° | 1° | 2° | Gaussians, no shift | Gaussians, CP |")
        out.append("|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            if r["sampler"] == "owen-sobol":
                continue
            o = os_rows[(r["N"], r["theta"])]
            g = lambda k: float(o[k]) / float(r[k]) if float(r[k]) > 0 else float("inf")
            out.append("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.3g | %.2f |" % (
                r["N"], r["theta"], r["sampler"], g("edge 0"), g("edge 0.5"), g("edge 1"), g("edge 2"),
                g("gauss0"), g("gauss-cp")))
        out.append("")
    sys.stdout.write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
