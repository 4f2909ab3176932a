#!/usr/bin/env python3
"""Whether any lattice reaches issue 25's edge goals at a given angle.

Reads the per-generator exact variances of alignset_lattice_frontier (TSV:
mode N theta g edge0 edge0.5 edge1 edge2) and Owen-Sobol's figures on the
same edges from the independent evaluator's tables (construction_eval.py's
TSVs, rows "owen-sobol"), and prints, per construction, N and theta:

  peak        the best any generator gives on the edge itself (Owen-Sobol / it);
  best        the generator that best meets all four goals together, scored by
              its slack min(gain0 / P, gain0.5 / 1, gain1 / 3, gain2 / 1)
              (P = 8 at N <= 1024, 20 above): at or above 1 it meets them;
  meeting     how many generators meet all four.

A column the frontier did not compute (alignset_lattice_frontier --deltas)
is nan and counts as met: the slack is then that of the columns measured.

  lattice_frontier.py FRONTIER.tsv[.gz] [...] --os EVAL.tsv [EVAL.tsv ...]

(g is the generator, or a/b/d, the dual basis of a lattice without one.)
"""
import argparse
import csv
import gzip
import math


def peak_goal(n):
    return 8.0 if n <= 1024 else 20.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("frontier", nargs="+")
    ap.add_argument("--os", nargs="+", required=True)
    a = ap.parse_args()
    cols = ["edge0", "edge0.5", "edge1", "edge2"]
    ref = {}
    for path in a.os:
        for r in csv.DictReader(open(path), delimiter="\t"):
            if r["sampler"] == "owen-sobol":
                ref[(int(r["N"]), float(r["theta"]))] = [float(r["edge %s" % d]) for d in ("0", "0.5", "1", "2")]
    rows = {}
    for path in a.frontier:
        text = gzip.open(path, "rt") if path.endswith(".gz") else open(path)
        for r in csv.DictReader(text, delimiter="\t"):
            key = (r["mode"], int(r["N"]), float(r["theta"]))
            rows.setdefault(key, []).append((r["g"], [float(r[c]) for c in cols]))
    print("| lattice | N | theta | peak (g) | best g: edge / +-0.5 / +-1 / +-2 | slack | meeting | generators |")
    print("|---|---:|---:|---|---|---:|---:|---:|")
    for (mode, n, theta), gens in sorted(rows.items()):
        if (n, theta) not in ref:
            continue
        o = ref[(n, theta)]
        need = [peak_goal(n), 1.0, 3.0, 1.0]
        gains = [(g, [o[i] / v[i] for i in range(4)]) for g, v in gens]
        peak_g, peak = max(gains, key=lambda x: x[1][0])
        slack = [(g, gn, min(gn[i] / need[i] for i in range(4) if not math.isnan(gn[i]))) for g, gn in gains]
        best_g, best, best_slack = max(slack, key=lambda x: x[2])
        meeting = sum(1 for s in slack if s[2] >= 1.0)
        print("| %s | %d | %g | %.1f (%s) | %s: %s | %.2f | %d | %d |" % (
            mode, n, theta, peak[0], peak_g, best_g, " / ".join("-" if math.isnan(x) else "%.1f" % x for x in best), best_slack, meeting,
            len(gens)))


if __name__ == "__main__":
    main()
