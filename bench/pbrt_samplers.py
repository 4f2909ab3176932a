#!/usr/bin/python3
"""pbrt-v4's samplers against alignset's "aligned" sampler, on the scenes of
integrations/pbrt-v4/scenes: MSE against a high-spp reference on edge pixels
and on the whole image, every sample counted, at equal samples and at equal
time, over several seeds; a table per scene variant and side-by-side images
with error maps.

It runs the pbrt binary that integrations/pbrt-v4/build.sh built and reads the
images it writes (PFM); it shares no code with the sampler it measures.

  /usr/bin/python3 bench/pbrt_samplers.py --pbrt build/pbrt-v4/bin/pbrt \
      --table build/pbrt-v4/lattice.tbl --out bench/results/pbrt

Edge pixels are read off the reference alone: a pixel whose reference
luminance differs from one of its eight neighbours' by more than --edge-tau of
the image's 99th-percentile luminance (a silhouette, a texture edge, a wire,
a penumbra's slope). No sampler's image takes part.

The reference is two renders with pbrt's zsobol at --ref-spp under other
seeds than any measured render; its own error (a quarter of the two halves'
mean squared difference) is reported beside the smallest MSE it judges.
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

SAMPLERS = ["zsobol", "paddedsobol", "sobol", "halton", "stratified", "independent", "aligned"]
# Diagnostics: which of the aligned sampler's dimensions carries the gain.
ALIGNED_VARIANTS = {
    "aligned": {},
    "aligned-film": {"align": "film"},
    "aligned-light": {"align": "light"},
    "aligned-none": {"align": "none"},
    "aligned-unpaired": {"pairwavelength": False},
}
# Scenes and the pixel filters each is measured under (pbrt's default, the
# Gaussian, always; the box where the filter's warp is the question), and
# pbrt's own spectral rendering (each sample's four wavelengths drawn from a
# sample dimension of their own) or, where the question is what that costs,
# --disable-wavelength-jitter (the wavelengths fixed: the same bias in the
# reference and every render, and no spectral noise).
VARIANTS = [
    ("soft_shadows", "box", ""), ("soft_shadows", "gaussian", ""),
    ("silhouettes", "box", ""), ("silhouettes", "gaussian", ""),
    ("thin_texture", "gaussian", ""),
    ("cornell_box", "gaussian", ""),
    ("silhouettes", "box", "fixed-wavelengths"), ("soft_shadows", "box", "fixed-wavelengths"),
    ("soft_shadows", "box", "fixed-film"),
]
# fixed-film: the film sample at the pixel's centre too (--disable-pixel-jitter):
# the pixel's integrand a function of its light sample alone.
FLAGS = {"": [], "fixed-wavelengths": ["--disable-wavelength-jitter"],
         "fixed-film": ["--disable-wavelength-jitter", "--disable-pixel-jitter"]}


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        dims = f.readline().split()
        while len(dims) < 2:
            dims += f.readline().split()
        w, h = int(dims[0]), int(dims[1])
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    img = data.reshape(h, w, channels).astype(np.float64)
    return img[::-1]  # PFM rows run bottom to top


def luminance(img):
    return img @ np.array([0.2126, 0.7152, 0.0722])


def scene_body(path):
    """The scene without its Sampler, PixelFilter and Film lines (the driver
    sets them)."""
    out = []
    with open(path) as f:
        for line in f:
            if re.match(r"\s*(Sampler|PixelFilter|Film)\b", line):
                continue
            out.append(line)
    return "".join(out)


class Renderer:
    def __init__(self, pbrt, table, res, work, threads):
        self.pbrt, self.table, self.res, self.work, self.threads = pbrt, table, res, work, threads
        self.count = 0
        self.flags = []

    def render(self, scene, filt, sampler, spp, seed, res=None, params=None):
        res = res or self.res
        base = sampler.split("-")[0]
        extra = ""
        if base == "aligned":
            extra = f' "string table" [ "{self.table}" ]' + param_text(params or {})
        # The count and the seed on pbrt's command line, which every sampler
        # reads (stratified has no "pixelsamples" of its own).
        self.count += 1
        return run_pbrt(self.pbrt, os.path.join(self.work, f"r{self.count}"), f'Sampler "{base}"{extra}\n',
                        filt, res, scene_body(scene), spp, seed, self.threads, self.flags, sampler)


def param_text(params):
    """pbrt's parameter list for a dict: bool, integer, a list of integers,
    or a string."""
    s = ""
    for k, v in params.items():
        if isinstance(v, bool):
            s += f' "bool {k}" [ {str(v).lower()} ]'
        elif isinstance(v, int):
            s += f' "integer {k}" [ {v} ]'
        elif isinstance(v, list):
            s += f' "integer {k}" [ {" ".join(str(x) for x in v)} ]'
        else:
            s += f' "string {k}" [ "{v}" ]'
    return s


def run_pbrt(pbrt, stem, sampler_line, filt, res, body, spp, seed, threads, flags, what):
    """Renders body under the sampler line, filter and a res x res film with
    pbrt's binary (stem.pbrt, stem.pfm, both removed after); returns the image
    and the wall-clock seconds."""
    out, wrapper = stem + ".pfm", stem + ".pbrt"
    with open(wrapper, "w") as f:
        f.write(sampler_line + f'PixelFilter "{filt}"\n'
                f'Film "rgb" "integer xresolution" [ {res} ] "integer yresolution" [ {res} ] '
                f'"string filename" [ "{out}" ]\n' + body)
    t0 = time.monotonic()
    p = subprocess.run([pbrt, "--quiet", "--nthreads", str(threads), "--spp", str(spp),
                        "--seed", str(seed)] + flags + [wrapper], capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if p.returncode != 0:
        raise RuntimeError(f"pbrt failed on {what} {spp} spp seed {seed}: {p.stderr.strip()[-800:]}")
    img = read_pfm(out)
    os.remove(out)
    os.remove(wrapper)
    return img, seconds


def neighbour_jump(y):
    """Each pixel's largest absolute difference from its eight neighbours'
    values (the image's border repeated)."""
    h, w = y.shape
    jump = np.zeros_like(y)
    pad = np.pad(y, 1, mode="edge")
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                jump = np.maximum(jump, np.abs(y - pad[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]))
    return jump


def edge_mask(ref, tau):
    y = luminance(ref)
    return neighbour_jump(y) > tau * np.percentile(y, 99)


def pixel_errors(img, ref):
    return ((img - ref) ** 2).mean(axis=2)


def run_record(sampler, spp, edge, whole, secs):
    """A sampler's row at one spp from its per-seed edge and whole-image
    errors and times: the means, their standard errors, the median time."""
    n = len(edge)
    return {"sampler": sampler, "spp": spp, "seeds": n,
            "edge": float(np.mean(edge)), "edge_se": float(np.std(edge, ddof=1) / math.sqrt(n)),
            "all": float(np.mean(whole)), "all_se": float(np.std(whole, ddof=1) / math.sqrt(n)),
            "seconds": float(np.median(secs))}


def loglog_at(xs, ys, x):
    """(ys at x, extrapolated): linear in log-log between the measured points
    that bracket x, or along the last (first) segment beyond them."""
    pts = sorted(zip(xs, ys))
    if len(pts) < 2:
        return None, False
    segments = list(zip(pts, pts[1:]))
    for (x0, y0), (x1, y1) in segments:
        if x0 <= x <= x1 and x1 > x0:
            t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0))), False
    (x0, y0), (x1, y1) = segments[-1] if x > pts[-1][0] else segments[0]
    t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
    return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0))), True


def measure_variant(r, scene_dir, scene, filt, mode, args, log):
    path = os.path.join(scene_dir, scene + ".pbrt")
    r.flags = FLAGS[mode]
    log(f"{scene} ({filt}{', ' + mode if mode else ''}): reference, 2 x {args.ref_spp} spp")
    ref_a, ta = r.render(path, filt, "zsobol", args.ref_spp, 100001)
    ref_b, tb = r.render(path, filt, "zsobol", args.ref_spp, 100002)
    ref = 0.5 * (ref_a + ref_b)
    mask = edge_mask(ref, args.edge_tau)
    ref_err = pixel_errors(ref_a, ref_b) / 4.0
    result = {
        "scene": scene, "filter": filt, "mode": mode or "spectral", "res": args.res, "ref_spp": 2 * args.ref_spp,
        "edge_pixels": int(mask.sum()), "pixels": int(mask.size), "edge_tau": args.edge_tau,
        "ref_error": {"edge": float(ref_err[mask].mean()), "all": float(ref_err.mean())},
        "runs": [],
    }
    images = {"reference": ref, "edge_mask": mask}
    samplers = [s for s in SAMPLERS if s in args.samplers]
    jobs = [(s, spp) for spp in args.spp for s in samplers]
    jobs += [(v, spp) for v in ALIGNED_VARIANTS if v != "aligned" and v in args.samplers
             for spp in args.diagnostic_spp]
    for sampler, spp in jobs:
        if sampler.startswith("aligned") and spp < 64:
            result["runs"].append({"sampler": sampler, "spp": spp, "skipped":
                                   "the aligned sampler needs 64 samples a pixel (a pre-pass of 16)"})
            continue
        seeds = args.seeds if spp < 1024 else max(2, args.seeds - 1)
        edge, whole, secs = [], [], []
        for k in range(seeds):
            img, s = r.render(path, filt, sampler, spp, 1 + k, params=ALIGNED_VARIANTS.get(sampler))
            e = pixel_errors(img, ref)
            edge.append(float(e[mask].mean()))
            whole.append(float(e.mean()))
            secs.append(s)
            if k == 0 and spp == args.image_spp and sampler in ("zsobol", "aligned"):
                images[f"{sampler}@{spp}"] = img
        run = run_record(sampler, spp, edge, whole, secs)
        result["runs"].append(run)
        log(f"  {sampler:>14} {spp:>5} spp: edge {run['edge']:.3e} +- {run['edge_se']:.1e}  "
            f"all {run['all']:.3e}  {run['seconds']:.1f} s")
    return result, images


def fmt(x):
    return f"{x:.2e}"


def table(result):
    """The variant's Markdown: MSE per sampler and spp on edge pixels and on
    the whole image, each sampler's ratio to aligned, and equal time."""
    runs = [x for x in result["runs"] if "skipped" not in x]
    by = {(x["sampler"], x["spp"]): x for x in runs}
    spps = sorted({x["spp"] for x in runs if x["sampler"] in SAMPLERS})
    mode = "" if result["mode"] == "spectral" else f", {result['mode']} ({' '.join(FLAGS[result['mode']])})"
    lines = [f"### {result['scene']}, {result['filter']} filter{mode}",
             "",
             f"{result['res']}² pixels, {result['edge_pixels']} of them edge pixels; reference "
             f"{result['ref_spp']} spp (zsobol), its own MSE {fmt(result['ref_error']['edge'])} on edge pixels, "
             f"{fmt(result['ref_error']['all'])} on the image.",
             ""]
    for region, name in (("edge", "Edge pixels"), ("all", "Whole image")):
        lines.append(f"{name}: MSE (mean over seeds), and in brackets its ratio to aligned's at the same spp "
                     f"(> 1: aligned lower).")
        lines.append("")
        lines.append("| sampler | " + " | ".join(f"{s} spp" for s in spps) + " |")
        lines.append("|---|" + "---:|" * len(spps))
        for s in [x for x in SAMPLERS if any(k[0] == x for k in by)]:
            cells = []
            for spp in spps:
                x = by.get((s, spp))
                if x is None:
                    cells.append("n/a")
                    continue
                a = by.get(("aligned", spp))
                ratio = f" ({x[region] / a[region]:.2f}×)" if a and s != "aligned" else ""
                cells.append(f"{fmt(x[region])} ± {x[region + '_se']:.0e}{ratio}")
            lines.append(f"| {s} | " + " | ".join(cells) + " |")
        lines.append("")
    # Equal time: zsobol's MSE at aligned's time, from zsobol's measured
    # (time, MSE) points, interpolated in log-log.
    z = sorted((x["seconds"], x) for x in runs if x["sampler"] == "zsobol")
    cells = []
    for spp in spps:
        a = by.get(("aligned", spp))
        if not a:
            continue
        ze, extra = loglog_at([t for t, _ in z], [x["edge"] for _, x in z], a["seconds"])
        za, _ = loglog_at([t for t, _ in z], [x["all"] for _, x in z], a["seconds"])
        mark = " (extrapolated)" if extra else ""
        cells.append(f"| {spp} | {a['seconds']:.1f} s | {ze / a['edge']:.2f}×{mark} | {za / a['all']:.2f}×{mark} |")
    if cells:
        lines += ["Equal time: zsobol's MSE at the aligned render's wall-clock time (interpolated in log-log "
                  "between zsobol's measured spp; beyond 1024 spp extrapolated along its 256-1024 slope), over "
                  "aligned's MSE (> 1: aligned lower).", "",
                  "| aligned spp | its time | edge pixels | whole image |", "|---:|---:|---:|---:|"] + cells + [""]
    diag = [x for x in runs if x["sampler"].startswith("aligned-")]
    if diag:
        lines += ["Which dimension carries the gain (the aligned sampler with only some dimensions aligned; "
                  "`none`: the pre-pass and the weighting with padded Owen-Sobol everywhere; `unpaired`: "
                  "the wavelength sample padded instead of paired with the aligned lattice):", "",
                  "| sampler | spp | edge MSE | whole-image MSE |", "|---|---:|---:|---:|"]
        for x in sorted(diag + [by[k] for k in by if k[0] in ("aligned", "zsobol")
                                and k[1] in {d["spp"] for d in diag}], key=lambda x: (x["spp"], x["sampler"])):
            lines.append(f"| {x['sampler']} | {x['spp']} | {fmt(x['edge'])} | {fmt(x['all'])} |")
        lines.append("")
    skipped = [x for x in result["runs"] if "skipped" in x and x["sampler"] == "aligned"]
    if skipped:
        lines += [f"Not run: aligned at {', '.join(str(x['spp']) for x in skipped)} spp ({skipped[0]['skipped']}).", ""]
    return "\n".join(lines)


def summary(results):
    """One line per variant: zsobol's MSE over aligned's on edge pixels and
    the whole image at 64 / 256 / 1024 spp, the best other sampler's at 256
    and 1024, and equal time."""
    lines = ["| scene | filter | mode | edge: zsobol / aligned at 64, 256, 1024 spp | edge: best other / aligned at 256, 1024 | "
             "image: zsobol / aligned at 64, 256, 1024 | equal time (edge) at 256, 1024 |",
             "|---|---|---|---|---|---|---|"]
    for r in results:
        runs = [x for x in r["runs"] if "skipped" not in x]
        by = {(x["sampler"], x["spp"]): x for x in runs}

        def ratio(sampler, spp, region):
            a, o = by.get(("aligned", spp)), by.get((sampler, spp))
            return f"{o[region] / a[region]:.2f}" if a and o else "–"

        def best(spp):
            a = by.get(("aligned", spp))
            others = [x for x in runs if x["spp"] == spp and x["sampler"] in SAMPLERS and x["sampler"] != "aligned"]
            if not a or not others:
                return "–"
            b = min(others, key=lambda x: x["edge"])
            return f"{b['edge'] / a['edge']:.2f} ({b['sampler']})"

        z = sorted((x["seconds"], x) for x in runs if x["sampler"] == "zsobol")
        eq = []
        for spp in (256, 1024):
            a = by.get(("aligned", spp))
            if a:
                v, extra = loglog_at([t for t, _ in z], [x["edge"] for _, x in z], a["seconds"])
                eq.append(f"{v / a['edge']:.2f}" + ("*" if extra else ""))
        lines.append(f"| {r['scene']} | {r['filter']} | {r.get('mode', 'spectral')} | "
                     + ", ".join(ratio("zsobol", n, "edge") for n in (64, 256, 1024)) + " | "
                     + ", ".join(best(n) for n in (256, 1024)) + " | "
                     + ", ".join(ratio("zsobol", n, "all") for n in (64, 256, 1024)) + " | "
                     + ", ".join(eq) + " |")
    return "\n".join(lines)


def figure(result, images, path, spp):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def tonemap(img):
        return np.clip(img / max(np.percentile(img, 99.5), 1e-9), 0, 1) ** (1 / 2.2)

    ref = images["reference"]
    panels = [("reference", tonemap(ref), None), ("edge pixels", images["edge_mask"], "gray")]
    errs = {}
    for s in ("zsobol", "aligned"):
        key = f"{s}@{spp}"
        if key in images:
            panels.append((f"{s}, {spp} spp", tonemap(images[key]), None))
            errs[s] = pixel_errors(images[key], ref)
    vmax = max((np.percentile(e, 99.5) for e in errs.values()), default=1.0)
    for s, e in errs.items():
        panels.append((f"{s} squared error", e, "magma"))
    fig, axes = plt.subplots(1, len(panels), figsize=(2.6 * len(panels), 2.9))
    for ax, (title, img, cmap) in zip(axes, panels):
        if cmap == "magma":
            ax.imshow(img, cmap=cmap, vmin=0, vmax=vmax, interpolation="nearest")
        else:
            ax.imshow(img, cmap=cmap, interpolation="nearest")
        ax.set_title(title, fontsize=8)
        ax.axis("off")
    fig.suptitle(f"{result['scene']}, {result['filter']} filter, {result['mode']} (error maps on one scale)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main_tables(args):
    results = []
    for scene, filt, mode in VARIANTS:
        name = f"{scene}_{filt}" + (f"_{mode}" if mode else "")
        path = os.path.join(args.out, name + ".json")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            results.append(json.load(f))
        with open(os.path.join(args.out, name + ".md"), "w") as f:
            f.write(table(results[-1]) + "\n")
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write(summary(results) + "\n\n\\* extrapolated beyond zsobol's 1024 spp along its 256-1024 slope\n")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pbrt", default="build/pbrt-v4/bin/pbrt")
    ap.add_argument("--table", default="build/pbrt-v4/lattice.tbl")
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "..", "integrations", "pbrt-v4", "scenes"))
    ap.add_argument("--out", default="bench/results/pbrt")
    ap.add_argument("--variants", default="all", help="scene:filter[:fixed-wavelengths],... (default: all eight)")
    ap.add_argument("--samplers", default=",".join(SAMPLERS + list(ALIGNED_VARIANTS)[1:]))
    ap.add_argument("--spp", default="16,64,256,1024")
    ap.add_argument("--diagnostic-spp", default="256", help="spp of the aligned-film/-light/-none runs")
    ap.add_argument("--seeds", type=int, default=3, help="seeds per run (one fewer at 1024 spp, at least 2)")
    ap.add_argument("--res", type=int, default=48)
    ap.add_argument("--ref-spp", type=int, default=16384)
    ap.add_argument("--edge-tau", type=float, default=0.03)
    ap.add_argument("--image-spp", type=int, default=256)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--tables-only", action="store_true", help="rewrite each .md from its .json, render nothing")
    args = ap.parse_args()
    if args.tables_only:
        return main_tables(args)
    args.spp = [int(x) for x in args.spp.split(",")]
    args.diagnostic_spp = [int(x) for x in args.diagnostic_spp.split(",") if x]
    args.samplers = args.samplers.split(",")
    variants = VARIANTS if args.variants == "all" else [tuple((v + "::").split(":")[:3]) for v in args.variants.split(",")]
    os.makedirs(args.out, exist_ok=True)
    t0 = time.monotonic()

    def log(msg):
        print(f"[{time.monotonic() - t0:7.0f} s] {msg}", flush=True)

    with tempfile.TemporaryDirectory() as work:
        r = Renderer(os.path.abspath(args.pbrt), os.path.abspath(args.table), args.res, work, args.threads)
        for scene, filt, mode in variants:
            result, images = measure_variant(r, os.path.abspath(args.scenes), scene, filt, mode, args, log)
            name = f"{scene}_{filt}" + (f"_{mode}" if mode else "")
            with open(os.path.join(args.out, name + ".json"), "w") as f:
                json.dump(result, f, indent=1)
            with open(os.path.join(args.out, name + ".md"), "w") as f:
                f.write(table(result) + "\n")
            figure(result, images, os.path.join(args.out, name + ".png"), args.image_spp)
            log(f"{name}: wrote {args.out}/{name}.{{json,md,png}}")
    # The tables and the summary over every variant measured so far.
    return main_tables(args)


if __name__ == "__main__":
    sys.exit(main())
