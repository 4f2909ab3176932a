#!/usr/bin/python3
"""The supplement's figures, reproduced with alignset (issue 14).

  /usr/bin/python3 bench/figures/supplement.py fig1      # spectrum loss, SW loss, both
  /usr/bin/python3 bench/figures/supplement.py fig2      # misalignment 0.25° ... 6°, 90°
  /usr/bin/python3 bench/figures/supplement.py fig3      # polygons with k = 3 ... 10 edge directions
  /usr/bin/python3 bench/figures/supplement.py fig4      # the domain's own edges: isotropic vs H/V
  /usr/bin/python3 bench/figures/supplement.py fig6      # CP against no CP, Owen-Sobol and CMJ
  /usr/bin/python3 bench/figures/supplement.py spectra   # expected power spectra, 1 and 2 directions
  /usr/bin/python3 bench/figures/supplement.py all

Every figure is made by the alignset CLI alone: `optimize` for the sets (default
settings unless the figure is about a setting), `sample` for the baselines,
`convergence --json` for variance against N and `analyze --json` for spectra; the
PNGs are drawn by scripts/plot_analysis.py, the one plotting path. Each writes
bench/results/<fig>.png and <fig>.txt (the table docs/results.md quotes).

Optimized sets are kept under build/figures/<version>/, where <version> is a hash
of `alignset --version` (release, algorithm version, default profile): when the
optimizer's defaults change, the figures regenerate from new sets by themselves.
"""
import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NS = [256, 1024, 4096]


class Runner:
    def __init__(self, args):
        self.cli = args.cli
        self.threads = args.threads
        self.force = args.force
        self.results = args.results
        version = self.run(["--version"])
        self.version = version.strip().replace("\n", "; ")
        tag = hashlib.sha256(version.encode()).hexdigest()[:10]
        self.sets_dir = os.path.join(args.work, tag)
        os.makedirs(self.sets_dir, exist_ok=True)
        os.makedirs(self.results, exist_ok=True)

    def run(self, argv):
        r = subprocess.run([self.cli] + argv, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"failed: alignset {' '.join(argv)}\n{r.stdout}{r.stderr}")
        return r.stdout

    def path(self, name):
        return os.path.join(self.sets_dir, name)

    def optimize(self, name, n, dirs, seeds, extra=()):
        """m optimized sets (seeds 1..m) in one .npy; made once per version."""
        out = self.path(f"{name}_n{n}.npy")
        if os.path.exists(out) and not self.force:
            return out
        argv = ["optimize", "-n", str(n), "-m", str(seeds), "-o", out, "--engine", "fast",
                "--threads", str(self.threads)]
        for d in dirs:
            argv += ["--dir", f"{d:g}"]
        t0 = time.time()
        self.run(argv + list(extra))
        print(f"  optimized {name} N={n} x{seeds}: {time.time() - t0:.1f} s", flush=True)
        return out

    def sample(self, name, sampler, n, seeds, shear=None):
        out = self.path(f"{name}_n{n}.npy")
        if os.path.exists(out) and not self.force:
            return out
        argv = ["sample", sampler, "-n", str(n), "-m", str(seeds), "-o", out]
        if shear is not None:
            argv += ["--shear", f"{shear:g}"]
        self.run(argv)
        return out

    def convergence(self, sets, samplers, integrands, ns, extra=()):
        """sets: {label: pattern with {n}}; returns the parsed JSON document."""
        argv = ["convergence", "--json", "-n", ",".join(map(str, ns))]
        for label, pattern in sets.items():
            argv += ["--set", f"{label}={pattern}"]
        for s in samplers:
            argv += ["--sampler", s]
        for f in integrands:
            argv += ["--integrand", f]
        return json.loads(self.run(argv + list(extra)))

    def analyze(self, path, title, dirs, max_freq):
        argv = ["analyze", path, "--json", "--title", title, "--max-freq", str(max_freq)]
        for d in dirs:
            argv += ["--dir", f"{d:g}"]
        return json.loads(self.run(argv))

    def plot(self, doc, name):
        data = self.path(f"{name}.json")
        with open(data, "w") as f:
            json.dump(doc, f)
        png = os.path.join(self.results, f"{name}.png")
        r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts/plot_analysis.py"),
                            data, "--out", png], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"plotting {name} failed:\n{r.stderr}")
        return png

    def write_table(self, name, command, lines):
        path = os.path.join(self.results, f"{name}.txt")
        with open(path, "w") as f:
            f.write(f"# {command}\n# {self.version}\n")
            f.write("\n".join(lines) + "\n")
        print("\n".join(lines))
        print(f"wrote {path} and {os.path.join(self.results, name + '.png')}")


def series_table(doc, ns, keys=("label", "integrand")):
    """Rows 'label | integrand | var@N ... | slope' from a convergence document."""
    head = "| " + " | ".join(keys) + " | " + " | ".join(f"N={n}" for n in ns) + " | slope |"
    rows = [head, "|" + "---|" * (len(keys) + len(ns) + 1)]
    for s in doc["series"]:
        cells = [str(s[k]) for k in keys] + [f"{v:.3e}" for v in s["variance"]]
        rows.append("| " + " | ".join(cells) + f" | {s['slope']:+.2f} |")
    return rows


def pattern(path):
    """build/.../name_n1024.npy -> build/.../name_n{n}.npy"""
    head, tail = path.rsplit("_n", 1)
    return head + "_n{n}" + tail[tail.index("."):]


def fig1(r, a):
    theta = 30
    variants = {  # label: (file key, optimize options)
        "spectrum + SW (default)": ("both", []),
        "spectrum loss only": ("spec", ["--sw-weight", "1e-30"]),
        "SW loss only": ("sw", ["--spectrum-weight", "0", "--revert-on", "total"]),
    }
    sets = {}
    for label, (key, extra) in variants.items():
        key = "fig1_" + key
        for n in NS:
            p = r.optimize(key, n, [theta], a.seeds, extra)
        sets[label] = pattern(p)
    ints = [f"step:{theta}", f"step:{theta}:0.13", f"smoothstep:{theta}:0.02"]
    doc = r.convergence(sets, ["owen-sobol"], ints, NS,
                        ["-m", str(a.scrambles), "--shifts", str(a.shifts)])
    doc["title"] = f"Fig. 1: losses, aligned edges θ = {theta}° ({a.seeds} sets per N)"
    r.plot(doc, "fig1_losses")
    r.write_table("fig1_losses", "bench/figures/supplement.py fig1",
                  series_table(doc, NS))


def fig2(r, a):
    theta = 30
    for n in NS:
        p = r.optimize("aligned30", n, [theta], a.seeds)
        q = r.sample("pmj02bn_sheared30", "pmj02bn", n, a.scrambles, shear=theta)
    offsets = [0, 0.25, 0.5, 1, 2, 3, 4, 5, 6, 90]
    series = []
    for d in offsets:
        doc = r.convergence({f"aligned 30°, edge {theta + d:g}° (off {d:g}°)": pattern(p)}, [],
                            [f"step:{theta + d:g}"], NS, ["--shifts", str(a.shifts)])
        s = doc["series"][0]
        s["integrand"] = "aligned set against misaligned edges"
        s["offset"] = d
        series.append(s)
    base = r.convergence({"pmj02bn sheared to 30°": pattern(q)}, ["owen-sobol"],
                         [f"step:{theta + 2}"], NS,
                         ["-m", str(a.scrambles), "--shifts", str(a.shifts)])
    for s in base["series"]:
        s["label"] += f", edge {theta + 2}°"
        s["integrand"] = "aligned set against misaligned edges"
        s["offset"] = 2
        series.append(s)
    doc = {"kind": "convergence", "title": f"Fig. 2: misalignment (sets for {theta}°)",
           "series": series}
    r.plot(doc, "fig2_misalignment")
    r.write_table("fig2_misalignment", "bench/figures/supplement.py fig2",
                  series_table(doc, NS, keys=("label",)))


def polygon_directions(k):
    """0°, 90° and k - 2 more: ceil((k-2)/2) spread evenly inside (0°, 90°), the rest
    inside (90°, 180°), so the directions are as far from each other and the axes
    as this split allows (k = 3: 45°; k = 6: 30, 60, 120, 150)."""
    m = k - 2
    first, second = (m + 1) // 2, m // 2
    dirs = [90.0 * (i + 1) / (first + 1) for i in range(first)]
    dirs += [90.0 + 90.0 * (i + 1) / (second + 1) for i in range(second)]
    return [round(d, 2) for d in dirs]


def fig3(r, a):
    series, lines = [], []
    summary = ["| k | arbitrary directions | aligned N=4096 | Owen-Sobol N=4096 | Owen-Sobol / aligned | "
               "aligned slope | Owen-Sobol slope |", "|---|---|---|---|---|---|---|"]
    for k in range(3, 11):
        dirs = polygon_directions(k)
        for n in NS:
            p = r.optimize(f"fig3_k{k}", n, dirs, a.seeds)
        spec = "edges:" + ":".join(f"{d:g}" for d in [0, 90] + dirs)
        doc = r.convergence({f"aligned for k {k}": pattern(p)}, ["owen-sobol"], [spec], NS,
                            ["-m", str(a.scrambles), "--shifts", str(a.shifts)])
        mine = next(s for s in doc["series"] if s["label"].startswith("aligned"))
        sobol = next(s for s in doc["series"] if s["label"] == "owen-sobol")
        sobol["label"] = f"Owen-Sobol, k {k}"
        series += doc["series"]
        ratio = sobol["variance"][-1] / mine["variance"][-1]
        summary.append(f"| {k} | {', '.join(f'{d:g}' for d in dirs)} | {mine['variance'][-1]:.3e} | "
                       f"{sobol['variance'][-1]:.3e} | {ratio:.2f} | {mine['slope']:+.2f} | "
                       f"{sobol['slope']:+.2f} |")
    doc = {"kind": "convergence", "series": series,
           "title": "Fig. 3: polygons with k edge directions, sets optimized for their k"}
    r.plot(doc, "fig3_polygons")
    r.write_table("fig3_polygons", "bench/figures/supplement.py fig3",
                  summary + [""] + series_table(doc, NS))


def fig4(r, a):
    # The current defaults clamp every step onto the axis-stratified sets, so
    # they cannot make an isotropic set: the comparison the supplement draws
    # uses its own profile (flat loss, no clamp) for both sets, and the
    # current default H/V set is shown beside them.
    sup = ["--profile", "supplement"]
    for n in NS:
        # H/V: the axes' strips and SW terms (an arbitrary 0° adds nothing new).
        p = r.optimize("fig4_hv_supplement", n, [0], a.seeds, sup)
        # Isotropic: the same disk, no strips (length and width 0), no SW term.
        q = r.optimize("fig4_iso_supplement", n, [0], a.seeds,
                       sup + ["--length", "0", "--width", "0", "--sw-weight", "1e-30"])
        c = r.optimize("fig4_hv", n, [0], a.seeds)
    sets = {"isotropic blue noise (supplement profile)": pattern(q),
            "H/V strips + disk (supplement profile)": pattern(p),
            "H/V, current defaults (--dir 0)": pattern(c)}
    doc = r.convergence(sets, ["owen-sobol"], ["boundary", "gaussian:0.3", "disk"], NS,
                        ["-m", str(a.scrambles), "--shifts", str(a.shifts)])
    doc["title"] = "Fig. 4: the domain's own edges (boundary ramp; wide clipped Gaussian; disk)"
    r.plot(doc, "fig4_domain_edges")
    spec = r.analyze(q.replace(f"_n{NS[-1]}", "_n1024"), "isotropic set, N = 1024", [], 64)
    spec_hv = r.analyze(p.replace(f"_n{NS[-1]}", "_n1024"), "H/V set, N = 1024", [], 64)
    r.plot([spec, spec_hv], "fig4_spectra")
    r.write_table("fig4_domain_edges", "bench/figures/supplement.py fig4", series_table(doc, NS))


def fig6(r, a):
    ns = NS + [4 * NS[-1]]
    ints = ["step:30", "triangle", "smoothstep:30:0.1"]
    # CP: 16 scrambles x shifts; no CP: the variance over many scrambles.
    cp = r.convergence({}, ["owen-sobol", "cmj"], ints, ns,
                       ["-m", str(a.scrambles), "--shifts", str(a.shifts // 4)])
    plain = r.convergence({}, ["owen-sobol", "cmj"], ints, ns,
                          ["--homogenize", "none", "-m", str(a.plain_seeds)])
    for s in cp["series"]:
        s["label"] += " (CP)"
    for s in plain["series"]:
        s["label"] += " (no CP)"
    doc = {"kind": "convergence", "series": cp["series"] + plain["series"]}
    doc["title"] = "Fig. 6: CP against no CP (discontinuous: step, triangle; smoothed: smoothstep 0.1)"
    r.plot(doc, "fig6_homogenization")
    r.write_table("fig6_homogenization", "bench/figures/supplement.py fig6",
                  series_table(doc, ns))


def spectra(r, a):
    n, theta, pair = 1024, 30, (30, 100)
    rows = []
    docs = [
        r.analyze(r.optimize("aligned30", n, [theta], a.seeds), f"aligned, θ = {theta}°",
                  [theta], 64),
        r.analyze(r.optimize("aligned30_100", n, list(pair), a.seeds),
                  f"aligned, θ = {pair[0]}°, {pair[1]}°", list(pair), 64),
        r.analyze(r.sample("owen_sobol", "owen-sobol", n, a.scrambles), "Owen-Sobol", [theta], 64),
        r.analyze(r.sample("pmj02bn_sheared30", "pmj02bn", n, a.scrambles, shear=theta),
                  f"pmj02bn sheared to {theta}°", [theta], 64),
        r.analyze(r.sample("rank1", "rank1-lattice", n, a.scrambles), "rank-1 lattice", [theta], 64),
    ]
    r.plot(docs, "spectra")
    rows.append("| set | sets | radial |v|=2 | |v|=8 | |v|=16 | |v|=32 | along 0° [1,16] | along 90° [1,16] "
                "| along 30° [1,16] | along 30° [17,64] |")
    rows.append("|---|---|---|---|---|---|---|---|---|---|")
    for d in docs:
        prof = {p["deg"]: p["power"] for p in d["directional"]}
        def mean(v, lo, hi):
            xs = [x for x in v[lo:hi + 1] if x is not None]  # None: no frequency on the line
            return sum(xs) / len(xs)
        rows.append(f"| {d['title']} | {d['sets']} | " +
                    " | ".join(f"{d['radial'][q]:.2g}" for q in (2, 8, 16, 32)) + " | " +
                    " | ".join(f"{mean(prof[g], 1, 16):.2g}" for g in (0, 90, 30)) +
                    f" | {mean(prof[30], 17, 64):.2g} |")
    r.write_table("spectra", "bench/figures/supplement.py spectra", rows)


FIGURES = {"fig1": fig1, "fig2": fig2, "fig3": fig3, "fig4": fig4, "fig6": fig6,
           "spectra": spectra}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("figure", choices=list(FIGURES) + ["all"])
    ap.add_argument("--cli", default=os.path.join(ROOT, "build/cli/alignset"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build/figures"))
    ap.add_argument("--results", default=os.path.join(ROOT, "bench/results"))
    ap.add_argument("--seeds", type=int, default=2, help="optimized sets per N")
    ap.add_argument("--scrambles", type=int, default=16, help="baseline sets per N")
    ap.add_argument("--plain-seeds", type=int, default=256, help="sets per N without CP (fig6)")
    ap.add_argument("--shifts", type=int, default=2048)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--n", default="256,1024,4096", help="point counts (fig6 adds 4 N)")
    ap.add_argument("--force", action="store_true", help="re-make sets already on disk")
    a = ap.parse_args()
    NS[:] = [int(x) for x in a.n.split(",")]
    r = Runner(a)
    for name in (FIGURES if a.figure == "all" else [a.figure]):
        t0 = time.time()
        print(f"== {name}", flush=True)
        FIGURES[name](r, a)
        print(f"== {name}: {time.time() - t0:.0f} s", flush=True)


if __name__ == "__main__":
    main()
