#!/usr/bin/env python3
"""The rendered comparison over scene seeds (bench/render/seeds.sh): one
markdown table per N of edge-, smooth- and whole-image MSE, each sampler
against Owen-Sobol at the same N and, for the samplers that spend a pre-pass
on the pixel's direction, against every baseline at the same total number
of samples per pixel (N + the pre-pass).

  seed_table.py --raw DIR --seeds "1 2 3" --n 256,1024,4096 --out FILE.md

The pre-pass and its evaluations per pixel come from each seed's
estimator.csv (render_bench's record of the estimator it ran).
"""
import argparse
import csv
import os
import sys

from ratios import ratio_text

# The samplers that read an estimated direction pay for its pre-pass; a
# "+reuse" or "+unbiased" variant folds the pre-pass into its estimate and
# pays the same.
ESTIMATED = {"aligned", "aligned-lattice", "aligned-tent-lattice", "pmj02bn-sheared"}


def estimated(sampler):
    return sampler.split("+")[0] in ESTIMATED


def read(path):
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            rows[(r["scene"], r["sampler"], int(r["n"]))] = r
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raw", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--n", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    seeds = a.seeds.split()
    ns = [int(n) for n in a.n.split(",")]
    prepasses = set()
    for s in seeds:
        with open(os.path.join(a.raw, "seed" + s, "estimator.csv")) as f:
            prepasses |= {(r["prepass"], int(r["evaluations"])) for r in csv.DictReader(f)}
    if len(prepasses) != 1:
        sys.exit("seed_table.py: the seeds ran different pre-passes: %s" % sorted(prepasses))
    prepass, prepass_evals = prepasses.pop()
    runs = {}
    for s in seeds:
        runs[s] = read(os.path.join(a.raw, "seed" + s, "render_errors.csv"))
        counted = os.path.join(a.raw, "seed" + s + "-counted", "render_errors.csv")
        if os.path.exists(counted):
            runs[s].update(read(counted))
    scenes = sorted({k[0] for r in runs.values() for k in r})
    samplers = []
    for r in runs.values():
        for k in r:
            if k[2] in ns and k[1] not in samplers:
                samplers.append(k[1])
    out = []
    out.append("# Rendered edge pixels over scene seeds %s, every sample counted\n" % ", ".join(seeds))
    out.append("Written by `bench/render/seed_table.py` from `bash bench/render/seeds.sh` "
               "(SEEDS=\"%s\", N=%s). Each seed is a different scene; 128×128 pixels; the "
               "direction of `aligned` and `aligned-lattice` is estimated per pixel from a "
               "pre-pass of %d evaluations (%s), which the *total spp* column counts; "
               "the `-exact` rows read the geometry's direction (a bound, no pre-pass). "
               "Ratios are Owen-Sobol's MSE over the sampler's (above 1: the sampler wins), "
               "the geometric mean over seeds with the range in brackets. The *OS / sampler* "
               "columns compare at the same N (the pre-pass not counted: the old accounting); "
               "the last two compare at the same total samples per pixel, the baselines "
               "rendered again at N + the pre-pass (the best of Owen-Sobol, pmj02bn, rank-1 "
               "lattice and screen-space rank-1 per seed). A `+reuse` row folds its pre-pass into "
               "the estimate, a pixel without a direction continuing the pre-pass's Owen-Sobol "
               "sequence (the renderer's default); a `+unbiased` row weights the pre-pass by the "
               "counts on every pixel (render/prepass_reuse.h).\n"
               % (" ".join(seeds), a.n, prepass_evals, prepass))
    for scene in scenes:
        for n in ns:
            out.append("\n## %s, N = %d\n" % (scene, n))
            out.append("| sampler | total spp | edge MSE per seed | OS / sampler, edge | "
                       "OS / sampler, smooth | OS / sampler, all | OS at the same total spp / sampler, edge | "
                       "best baseline at the same total spp / sampler, edge | "
                       "OS at the same total spp / sampler, smooth | "
                       "best baseline at the same total spp / sampler, all |")
            out.append("|---|---:|---|---|---|---|---|---|---|---|")
            for smp in samplers:
                per = [runs[s].get((scene, smp, n)) for s in seeds]
                if any(p is None for p in per):
                    continue
                os_ = [runs[s].get((scene, "owen-sobol", n)) for s in seeds]
                total = n + (prepass_evals if estimated(smp) else 0)
                edge = [float(p["mse_edge"]) for p in per]
                r_edge = [float(o["mse_edge"]) / e for o, e in zip(os_, edge) if o and e > 0]
                r_smooth = [float(o["mse_smooth"]) / float(p["mse_smooth"])
                            for o, p in zip(os_, per) if o and float(p["mse_smooth"]) > 0]
                r_all = [float(o["mse_all"]) / float(p["mse_all"]) for o, p in zip(os_, per) if o]
                counted = os_counted = os_counted_smooth = counted_all = "—"
                if estimated(smp):
                    def against(reference, col):
                        # reference(run, col): the other sampler's MSE at the same
                        # total spp in that seed's run, or None.
                        return ratio_text([reference(runs[s], col) / float(p[col])
                                           for s, p in zip(seeds, per)
                                           if reference(runs[s], col) is not None and float(p[col]) > 0])

                    def owen_sobol(run, col):
                        row = run.get((scene, "owen-sobol", total))
                        return float(row[col]) if row else None

                    def best_baseline(run, col):
                        cands = [float(r[col]) for k, r in run.items()
                                 if k[0] == scene and k[2] == total and not estimated(k[1])
                                 and not k[1].endswith("-exact")]
                        return min(cands) if cands else None

                    os_counted = against(owen_sobol, "mse_edge")
                    counted = against(best_baseline, "mse_edge")
                    os_counted_smooth = against(owen_sobol, "mse_smooth")
                    counted_all = against(best_baseline, "mse_all")
                out.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    smp, total, ", ".join("%.3g" % e for e in edge), ratio_text(r_edge),
                    ratio_text(r_smooth), ratio_text(r_all), os_counted, counted,
                    os_counted_smooth, counted_all))
    text = "\n".join(out) + "\n"
    with open(a.out, "w") as f:
        f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
