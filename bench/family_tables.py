#!/usr/bin/python3
"""Markdown tables of bench/integrand_family.sh's TSV files (docs/results.md, "Integrand family").

For each profile: the ratio aligned / Owen-Sobol (16 scrambles) of every
family member at every (θ, N), the worst ratio per member, and the fitted
log-log slopes of the aligned step edge over N.

  /usr/bin/python3 bench/family_tables.py bench/results/family_current.tsv \
      [bench/results/family_supplement.tsv ...]
"""
import csv
import math
import sys
from collections import defaultdict


def slope(ns, vs):
    xs = [math.log(n) for n in ns]
    ys = [math.log(v) for v in vs]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def table(path):
    rows = list(csv.DictReader(open(path), delimiter="\t"))
    members = []
    for r in rows:
        if r["integrand"] not in members:
            members.append(r["integrand"])
    cells = defaultdict(dict)
    values = defaultdict(dict)
    for r in rows:
        key = (float(r["theta"]), int(r["n"]))
        cells[key][r["integrand"]] = float(r["ratio"])
        values[key][r["integrand"]] = (float(r["aligned"]), float(r["owen_sobol"]))
    print(f"`{path}`: aligned / Owen-Sobol (below 1: alignset better)\n")
    print("| θ | N | " + " | ".join(members) + " |")
    print("|---:|---:|" + "---:|" * len(members))
    for key in sorted(cells):
        print(f"| {key[0]:g} | {key[1]} | " +
              " | ".join(f"{cells[key].get(m, float('nan')):.3f}" for m in members) + " |")
    worst = {m: max(c.get(m, 0) for c in cells.values()) for m in members}
    print("| worst | | " + " | ".join(f"**{worst[m]:.3f}**" for m in members) + " |")
    print()
    thetas = sorted({k[0] for k in cells})
    print("| θ | slope aligned edge | slope Owen-Sobol | edge gain at each N |")
    print("|---:|---:|---:|---|")
    for t in thetas:
        ks = sorted(k for k in cells if k[0] == t)
        ns = [k[1] for k in ks]
        if len(ns) < 2:
            continue
        a = [values[k]["step theta"][0] for k in ks]
        o = [values[k]["step theta"][1] for k in ks]
        gains = ", ".join(f"{n}: {oo / aa:.1f}x" for n, aa, oo in zip(ns, a, o))
        print(f"| {t:g} | {slope(ns, a):.2f} | {slope(ns, o):.2f} | {gains} |")
    print()


for p in sys.argv[1:]:
    table(p)
