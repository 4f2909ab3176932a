#!/usr/bin/python3
"""A sampler in pbrt-v4 against pbrt's best, at equal samples and at equal
time: the joint lattice (the "aligned" sampler with align "joint") and any
other sampler named, against zsobol (pbrt's default) and sobol (pbrt's best
on the edge pixels measured so far), on the scenes of
integrations/pbrt-v4/scenes with direct lighting and with "path" at depth 5.

  /usr/bin/python3 bench/pbrt_equal_time.py --pbrt build/pbrt-v4/bin/pbrt \
      --out bench/results/pbrt_joint

The error is relative: per pixel, the squared difference from the reference
over (reference^2 + 0.01^2), averaged over RGB; then averaged over the edge
pixels (or every pixel) with the largest 0.1% of pixel errors trimmed
(fireflies) and emitter pixels left out. Edge pixels are read off the
reference alone (a jump to a neighbour above --edge-tau of the 99th
percentile luminance); emitter pixels are those of the reference brighter
than a quarter of its brightest where that pixel stands out over 10 times
the 90th percentile (a light seen directly), and every pixel whose filter
reaches one. The reference is pbrt's zsobol
at --ref-factor times the highest spp measured, under a seed no measured
render uses, kept in --ref-cache (keyed by the scene's text, resolution and
spp) for the next run. Equal time: each baseline's error at the subject's median
wall-clock time, interpolated in log-log between the baseline's measured
spp (extrapolated along its last segment, marked *, beyond them).

The floor (--floor, or --add-floor for tables already measured): the part of
every sampler's error that no sampler reaches. pbrt's layered BSDFs
(coateddiffuse, coatedconductor) evaluate and sample themselves by a random
walk whose random numbers come from pbrt's --seed hashed with the
directions, not from the sampler. zsobol is rendered twice with its own
seed fixed and two --seed values: the sampler's points are the same, the
walk's numbers are not, and half the two images' squared difference (the
relative error's normalisation, trimmed as the errors are) is that walk's
variance. It is the same for every sampler in expectation (each samples the
same directions' distribution), so each table also gives every sampler's
error net of it, at equal samples and at equal time. The acceptance figures
stay the raw ones: a user's render has the floor in it.

It runs pbrt's binary and reads the PFM images it writes; it shares no code
with the samplers it measures.
"""

import argparse
import hashlib
import json
import math
import os
import re
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pbrt_samplers import loglog_at, luminance, neighbour_jump, param_text, run_pbrt, run_record  # noqa: E402

BASELINES = ["zsobol", "sobol"]
# The measured samplers: pbrt's name and parameters.
SAMPLERS = {
    "zsobol": ("zsobol", {}),
    "sobol": ("sobol", {}),
    "paddedsobol": ("paddedsobol", {}),
    "joint": ("aligned", {"align": "joint"}),
    # The joint lattice over the film and the light sample only (the rest padded).
    "joint-film-light": ("aligned", {"align": "joint", "jointdimensions": [5, 6]}),
    # Over the film and the wavelength only.
    "joint-film-wavelength": ("aligned", {"align": "joint", "jointdimensions": [0]}),
    # Over the film, the light sample and the wavelength (the BSDF's and the
    # light choice's dimensions padded).
    "joint-light-wavelength": ("aligned", {"align": "joint", "jointdimensions": [5, 6, 0]}),
    # The same lattice, each pixel's shift followed by the tent (the folded
    # wavelength left periodic).
    "joint-tent": ("aligned", {"align": "joint", "randomize": "tent"}),
    # Each lattice point jittered within its strata instead of shifted.
    "joint-jitter": ("aligned", {"align": "joint", "randomize": "jitter"}),
    # The tent in the first BSDF sample only (the film and light squares
    # shifted alone; tenting the lobe and light choice too gave the same
    # images on the six path variants).
    "joint-tent-bsdf": ("aligned", {"align": "joint", "tentdimensions": [8, 9]}),
    # The lattice the default is with a pinhole camera, named, whatever the
    # camera: what joint's lens and time dimensions are worth where the
    # camera has a lens (there the default puts them after the film).
    "joint-pinhole": ("aligned", {"align": "joint", "jointdimensions": [5, 6, 0, 8, 9, 7, 4]}),
}
# The floor's renders: zsobol's own seed, and two --seed values no measured
# render uses.
FLOOR_SAMPLER_SEED = 77
FLOOR_SEEDS = (800001, 800002)
# Pixels from a pixel's centre that pbrt's gaussian filter (radius 1.5) reaches.
FILTER_REACH = 2
SCENES = ["soft_shadows", "silhouettes", "thin_texture", "cornell_box", "room_sphere_light", "room_rect_light",
          "room_lens_motion"]
MODES = ["direct", "path5"]


def scene_text(path, mode):
    """The scene without its Sampler, PixelFilter and Film lines (the driver
    writes them), its integrator set by the mode: "direct" keeps the scene's
    own unless it has none (then path at depth 1), "path5" is path at depth 5."""
    out, integrator = [], None
    with open(path) as f:
        for line in f:
            if re.match(r"\s*(Sampler|PixelFilter|Film)\b", line):
                continue
            if re.match(r"\s*Integrator\b", line):
                integrator = line
                continue
            out.append(line)
    if mode == "path5":
        integrator = 'Integrator "path" "integer maxdepth" [ 5 ]\n'
    elif integrator is None:
        integrator = 'Integrator "path" "integer maxdepth" [ 1 ]\n'
    return integrator + "".join(out)


class Renderer:
    def __init__(self, pbrt, res, work, threads, table):
        self.pbrt, self.res, self.work, self.threads, self.table = pbrt, res, work, threads, table
        self.count = 0

    def render(self, text, sampler, spp, seed, sampler_seed=None):
        """sampler_seed: the sampler's own "seed" parameter, which otherwise
        is pbrt's --seed (the layered BSDFs' walk reads --seed alone)."""
        name, params = SAMPLERS[sampler]
        params = dict(params)
        if sampler_seed is not None:
            params["seed"] = sampler_seed
        if name == "aligned" and params.get("align") != "joint":
            params["table"] = self.table
        self.count += 1
        return run_pbrt(self.pbrt, os.path.join(self.work, f"r{self.count}"), f'Sampler "{name}"{param_text(params)}\n',
                        "gaussian", self.res, text, spp, seed, self.threads, [], sampler)


def masks(ref, tau):
    y = luminance(ref)
    emitter = np.zeros(y.shape, dtype=bool)
    if y.max() > 10 * max(np.percentile(y, 90), 1e-9):
        emitter = y > 0.25 * y.max()
        # A light's rim too: every pixel whose filter reaches the light. Its
        # value is the light's glow through the filter's tail, a rare hit worth
        # hundreds of times the pixel: on the Cornell box a one-pixel rim left a
        # row of such pixels, 25 of 5013 edge pixels with 90% of every
        # sampler's edge error.
        for _ in range(FILTER_REACH):
            emitter = (neighbour_jump(emitter.astype(float)) > 0) | emitter
    # The jump's scale from the lit scene, not the light: a light seen over 1%
    # of the image would set it and leave only the light's surroundings.
    edge = neighbour_jump(y) > tau * np.percentile(y[~emitter], 99)
    return edge & ~emitter, ~emitter


def rel_error(img, ref, other=None):
    """Per pixel, the squared difference of img from ref (or from `other`)
    relative to the reference, over RGB."""
    return (((img - (ref if other is None else other)) ** 2) / (ref ** 2 + 1e-4)).mean(axis=2)


def trimmed_mean(values, trim=0.001):
    v = np.sort(values.ravel())
    keep = len(v) - int(math.floor(trim * len(v)))
    return float(v[:keep].mean())


def floor(r, text, spp, ref, edge_mask, image_mask):
    """The floor at spp (the module's docstring): zsobol twice, its seed
    fixed, --seed changed; half the images' relative squared difference."""
    a, sa = r.render(text, "zsobol", spp, FLOOR_SEEDS[0], FLOOR_SAMPLER_SEED)
    b, sb = r.render(text, "zsobol", spp, FLOOR_SEEDS[1], FLOOR_SAMPLER_SEED)
    d = rel_error(a, ref, other=b) / 2
    return {"spp": spp, "edge": trimmed_mean(d[edge_mask]), "all": trimmed_mean(d[image_mask]),
            "seconds": float(np.median([sa, sb]))}


def add_floors(result, floors):
    """result's floors with `floors` in, replacing those at the same spp."""
    kept = [f for f in result.get("floors", []) if f["spp"] not in {x["spp"] for x in floors}]
    result["floors"] = sorted(kept + floors, key=lambda f: f["spp"])


def reference(r, text, scene, mode, ref_spp, args, log):
    """The reference image and its seconds: from --ref-cache, or rendered
    (zsobol, seed 900001: the same image every time) and kept there."""
    key = hashlib.sha256(f"{text}|{args.res}|{ref_spp}".encode()).hexdigest()[:16]
    cached = os.path.join(args.ref_cache, f"{scene}_{mode}_{key}.npz") if args.ref_cache else None
    if cached and os.path.exists(cached):
        with np.load(cached) as z:
            log(f"{scene} ({mode}): reference, zsobol at {ref_spp} spp, from {cached}")
            return z["image"], float(z["seconds"])
    log(f"{scene} ({mode}): reference, zsobol at {ref_spp} spp")
    ref, ref_seconds = r.render(text, "zsobol", ref_spp, 900001)
    if cached:
        os.makedirs(args.ref_cache, exist_ok=True)
        np.savez(cached + ".tmp.npz", image=ref, seconds=ref_seconds)
        os.replace(cached + ".tmp.npz", cached)
    return ref, ref_seconds


def measure(r, scene_dir, scene, mode, args, log):
    text = scene_text(os.path.join(scene_dir, scene + ".pbrt"), mode)
    ref_spp = args.ref_spp or args.ref_factor * max(args.spp)
    ref, ref_seconds = reference(r, text, scene, mode, ref_spp, args, log)
    edge_mask, image_mask = masks(ref, args.edge_tau)
    result = {"scene": scene, "mode": mode, "res": args.res, "ref_spp": ref_spp,
              "ref_seconds": ref_seconds, "edge_pixels": int(edge_mask.sum()),
              "emitter_pixels": int((~image_mask).sum()), "pixels": int(image_mask.size), "runs": []}
    images = {"reference": ref, "edge": edge_mask}
    for spp in args.spp:
        # Seed by seed, every sampler in turn: a drift in the machine's speed
        # (shared, noisy) falls on every sampler alike.
        per = {sampler: ([], [], []) for sampler in args.samplers}
        for k in range(args.seeds):
            for sampler in args.samplers:
                img, s = r.render(text, sampler, spp, 1 + k)
                e = rel_error(img, ref)
                edge, whole, secs = per[sampler]
                edge.append(trimmed_mean(e[edge_mask]))
                whole.append(trimmed_mean(e[image_mask]))
                secs.append(s)
                if k == 0 and spp == args.image_spp:
                    images[f"{sampler}@{spp}"] = img
        for sampler in args.samplers:
            run = run_record(sampler, spp, *per[sampler])
            result["runs"].append(run)
            log(f"  {sampler:>22} {spp:>5} spp: edge {run['edge']:.3e} +- {run['edge_se']:.1e}  "
                f"all {run['all']:.3e} +- {run['all_se']:.1e}  {run['seconds']:.2f} s")
        if args.floor:
            f = floor(r, text, spp, ref, edge_mask, image_mask)
            add_floors(result, [f])
            log(f"  {'floor':>22} {spp:>5} spp: edge {f['edge']:.3e}  all {f['all']:.3e}")
    return result, images


def measure_floor(r, scene_dir, scene, mode, args, log):
    """--add-floor: the floor at args.spp added to the stored table of
    (scene, mode), against the table's own reference and edge pixels."""
    name = f"{scene}_{mode}"
    path = os.path.join(args.out, name + ".json")
    with open(path) as f:
        result = json.load(f)
    text = scene_text(os.path.join(scene_dir, scene + ".pbrt"), mode)
    ref, _ = reference(r, text, scene, mode, result["ref_spp"], args, log)
    edge_mask, image_mask = masks(ref, args.edge_tau)
    if int(edge_mask.sum()) != result["edge_pixels"]:
        raise RuntimeError(f"{path}: {result['edge_pixels']} edge pixels, this reference {int(edge_mask.sum())} "
                           f"(another --edge-tau or --res?)")
    floors = []
    for spp in args.spp:
        floors.append(floor(r, text, spp, ref, edge_mask, image_mask))
        log(f"  {name} floor {spp:>5} spp: edge {floors[-1]['edge']:.3e}  all {floors[-1]['all']:.3e}")
    add_floors(result, floors)
    write_table(args, name, result)


def retime(r, old, scene_dir, scene, mode, args, log):
    """--retime: the frame times of args.samplers at args.spp measured again
    in the stored table of (scene, mode); the errors kept, each alignset
    sampler's seed-1 image checked against the old binary's."""
    name = f"{scene}_{mode}"
    path = os.path.join(args.out, name + ".json")
    with open(path) as f:
        result = json.load(f)
    text = scene_text(os.path.join(scene_dir, scene + ".pbrt"), mode)
    checked = {x for x in args.samplers if SAMPLERS[x][0] == "aligned"}  # pbrt's own samplers did not change
    for spp in args.spp:
        secs = {sampler: [] for sampler in args.samplers}
        for k in range(args.seeds):
            for sampler in args.samplers:
                img, s = r.render(text, sampler, spp, 1 + k)
                secs[sampler].append(s)
                if k == 0 and sampler in checked:
                    before, _ = old.render(text, sampler, spp, 1)
                    if not np.array_equal(img, before):
                        raise RuntimeError(f"{name} {sampler} {spp} spp: the image differs from {args.retime}'s; "
                                           "--retime keeps errors only where the images are the same")
        for sampler in args.samplers:
            runs = [x for x in result["runs"] if x["sampler"] == sampler and x["spp"] == spp]
            if len(runs) != 1:
                raise RuntimeError(f"{path}: no run of {sampler} at {spp} spp to retime")
            was = runs[0]["seconds"]
            runs[0]["seconds"] = float(np.median(secs[sampler]))
            runs[0]["timed_seeds"] = len(secs[sampler])  # the errors keep their own "seeds"
            same = " (the same image)" if sampler in checked else ""
            log(f"  {name} {sampler:>8} {spp:>5} spp: {was:.2f} s -> {runs[0]['seconds']:.2f} s{same}")
    write_table(args, name, result)


def write_table(args, name, result):
    """A variant's result as --out/name.json and its tables as name.md."""
    with open(os.path.join(args.out, name + ".json"), "w") as f:
        json.dump(result, f, indent=1)
    with open(os.path.join(args.out, name + ".md"), "w") as f:
        f.write(table(result, args.subject) + "\n")


def net_runs(result):
    """The runs at the spp the floor was measured at, each error net of the
    floor (None where the floor is not below it)."""
    floors = {f["spp"]: f for f in result.get("floors", [])}
    out = []
    for x in result["runs"]:
        f = floors.get(x["spp"])
        if f:
            out.append(dict(x, **{k: (x[k] - f[k] if x[k] > f[k] else None) for k in ("edge", "all")}))
    return out


def equal_time(runs, baseline, seconds, region):
    pts = sorted((x["seconds"], x[region]) for x in runs if x["sampler"] == baseline and x[region] is not None)
    return loglog_at([t for t, _ in pts], [e for _, e in pts], seconds)


def table(result, subject):
    runs = result["runs"]
    by = {(x["sampler"], x["spp"]): x for x in runs}
    spps = sorted({x["spp"] for x in runs})
    samplers = list(dict.fromkeys(x["sampler"] for x in runs))
    lines = [f"### {result['scene']}, {result['mode']}", "",
             f"{result['res']}² pixels, {result['edge_pixels']} edge pixels, {result['emitter_pixels']} emitter "
             f"pixels left out; reference zsobol at {result['ref_spp']} spp ({result['ref_seconds']:.0f} s).", ""]
    for region, name in (("edge", "Edge pixels"), ("all", "Whole image")):
        lines += [f"{name}: relative MSE (mean over seeds ± its standard error); in brackets the ratio to "
                  f"{subject}'s at the same spp (> 1: {subject} lower).", "",
                  "| sampler | " + " | ".join(f"{s} spp" for s in spps) + " |", "|---|" + "---:|" * len(spps)]
        for s in samplers:
            cells = []
            for spp in spps:
                x, a = by.get((s, spp)), by.get((subject, spp))
                if not x:
                    cells.append("n/a")
                    continue
                ratio = f" ({x[region] / a[region]:.2f}×)" if a and s != subject else ""
                cells.append(f"{x[region]:.2e} ± {x[region + '_se']:.0e}{ratio}")
            lines.append(f"| {s} | " + " | ".join(cells) + " |")
        lines.append("")
    lines += [f"Equal time: each baseline's relative MSE at {subject}'s wall-clock time over {subject}'s "
              f"(> 1: {subject} lower; * extrapolated), and its time over zsobol's at the same spp.", "",
              "| spp | time / zsobol's | edge: zsobol | edge: sobol | edge: better of the two | image: zsobol | "
              "image: sobol |", "|---:|---:|---:|---:|---:|---:|---:|"]
    for spp in spps:
        a, z = by.get((subject, spp)), by.get(("zsobol", spp))
        if not a or not z:
            continue
        cells, best = [], None
        for region in ("edge", "all"):
            for b in BASELINES:
                v, extra = equal_time(runs, b, a["seconds"], region)
                if v is None:
                    cells.append("–")
                    continue
                cells.append(f"{v / a[region]:.2f}{'*' if extra else ''}")
                if region == "edge":
                    best = v / a[region] if best is None else min(best, v / a[region])
            if region == "edge":
                cells.append(f"**{best:.2f}**" if best is not None else "–")
        lines.append(f"| {spp} | {a['seconds'] / z['seconds']:.2f} | " + " | ".join(cells) + " |")
    lines.append("")
    if result.get("floors"):
        lines += floor_table(result, subject)
    return "\n".join(lines)


def better_net(result, subject, spp, region, timed):
    """The better baseline's error net of the floor over the subject's, at
    equal samples (timed False) or at the subject's time: (ratio or None,
    extrapolated)."""
    net = net_runs(result)
    a = next((x for x in net if x["sampler"] == subject and x["spp"] == spp), None)
    if not a or a[region] is None:
        return None, False
    if not timed:
        same = [x[region] for x in net if x["sampler"] in BASELINES and x["spp"] == spp and x[region] is not None]
        return (min(same) / a[region], False) if same else (None, False)
    timed_values = [equal_time(net, b, a["seconds"], region) for b in BASELINES]
    timed_values = [(v, extra) for v, extra in timed_values if v is not None]
    if not timed_values:
        return None, False
    v, extra = min(timed_values)
    return v / a[region], extra


def floor_table(result, subject):
    by = {(x["sampler"], x["spp"]): x for x in result["runs"]}
    lines = ["The floor: the part of every sampler's error that pbrt's layered BSDFs' own random walk makes "
             "(zsobol twice, its seed fixed, pbrt's --seed changed: half the two images' relative squared "
             "difference); no sampler reaches it. Its share of the subject's error, and the better of zsobol "
             f"and sobol over {subject} with every error net of it (> 1: {subject} lower; * extrapolated; – "
             "where the floor is not below an error).", "",
             "| spp | floor, edge (share of the subject's) | floor, image | edge net, equal spp | edge net, equal time "
             "| image net, equal time |", "|---:|---:|---:|---:|---:|---:|"]
    for f in result["floors"]:
        a = by.get((subject, f["spp"]))
        share = {region: f" ({f[region] / a[region]:.0%})" if a else "" for region in ("edge", "all")}
        cells = []
        for region, timed in (("edge", False), ("edge", True), ("all", True)):
            v, extra = better_net(result, subject, f["spp"], region, timed)
            cells.append(f"{v:.2f}{'*' if extra else ''}" if v is not None else "–")
        lines.append(f"| {f['spp']} | {f['edge']:.2e}{share['edge']} | {f['all']:.2e}{share['all']} | "
                     + " | ".join(cells) + " |")
    lines.append("")
    return lines


def summary(out, subject):
    """One row a scene and mode from every table in `out`: the subject against
    the better of zsobol and sobol, at equal samples and at equal time. False,
    writing nothing, where no table has a run of the subject."""
    results = []
    for name in sorted(os.listdir(out)):
        if name.endswith(".json") and name != "summary.json":
            with open(os.path.join(out, name)) as f:
                results.append(json.load(f))
    spps = sorted({x["spp"] for r in results for x in r["runs"] if x["sampler"] == subject})
    if not spps:
        return False  # nothing of the subject's to sum up (the baselines alone)
    head = ", ".join(str(s) for s in spps)
    floored = any(r.get("floors") for r in results)
    net_note = (" The floor, where measured (–: not): each error net of what pbrt's layered BSDFs' own random walk "
                "adds to every sampler's (the scene's table says how it is measured).") if floored else ""
    net_head = "edge, equal time, net of the floor | " if floored else ""
    lines = ["# The joint lattice in pbrt-v4: summary", "",
             f"The better of zsobol's and sobol's relative MSE over {subject}'s (> 1: {subject} lower), on edge "
             f"pixels and on the whole image, at equal samples and at equal time (* extrapolated beyond the "
             f"baseline's measured spp); the last column {subject}'s frame time over zsobol's at "
             f"{spps[-1]} spp. Every number's table, with standard errors: the scene's .md beside this file." + net_note,
             "",
             f"| scene | mode | edge, equal spp (at {head} spp) | edge, equal time | image, equal spp | image, equal time "
             f"| {net_head}time / zsobol's |", "|---|---|---|---|---|---|" + ("---|" if floored else "") + "---:|"]
    for r in results:
        by = {(x["sampler"], x["spp"]): x for x in r["runs"]}
        cols = {k: [] for k in ("edge_spp", "edge_time", "all_spp", "all_time")}
        for spp in spps:
            a = by.get((subject, spp))
            for region in ("edge", "all"):
                if not a:
                    cols[region + "_spp"].append("–")
                    cols[region + "_time"].append("–")
                    continue
                same = [by[(b, spp)][region] for b in BASELINES if (b, spp) in by]
                cols[region + "_spp"].append(f"{min(same) / a[region]:.2f}" if same else "–")
                timed = [equal_time(r["runs"], b, a["seconds"], region) for b in BASELINES]
                timed = [(v, extra) for v, extra in timed if v is not None]
                if timed:
                    v, extra = min(timed)
                    cols[region + "_time"].append(f"{v / a[region]:.2f}{'*' if extra else ''}")
                else:
                    cols[region + "_time"].append("–")
        last = spps[-1]
        a, z = by.get((subject, last)), by.get(("zsobol", last))
        t = f"{a['seconds'] / z['seconds']:.2f}" if a and z else "–"
        if floored:
            nets = [better_net(r, subject, spp, "edge", True) for spp in spps]
            cols["edge_net"] = [f"{v:.2f}{'*' if extra else ''}" if v is not None else "–" for v, extra in nets]
        lines.append(f"| {r['scene']} | {r['mode']} | " + " | ".join(", ".join(cols[k]) for k in cols) + f" | {t} |")
    lines.append("")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines))
    return True


def figure(result, images, path, spp, samplers):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def tonemap(img):
        return np.clip(img / max(np.percentile(img, 99.5), 1e-9), 0, 1) ** (1 / 2.2)

    ref = images["reference"]
    shown = [s for s in samplers if f"{s}@{spp}" in images]
    errs = {s: rel_error(images[f"{s}@{spp}"], ref) for s in shown}
    vmax = max((np.percentile(e, 99.5) for e in errs.values()), default=1.0)
    fig, axes = plt.subplots(2, len(shown) + 1, figsize=(2.5 * (len(shown) + 1), 5.2),
                             squeeze=False)
    axes[0][0].imshow(tonemap(ref))
    axes[0][0].set_title("reference", fontsize=8)
    axes[1][0].imshow(images["edge"], cmap="gray", interpolation="nearest")
    axes[1][0].set_title("edge pixels", fontsize=8)
    for k, s in enumerate(shown, 1):
        axes[0][k].imshow(tonemap(images[f"{s}@{spp}"]))
        axes[0][k].set_title(f"{s}, {spp} spp", fontsize=8)
        axes[1][k].imshow(errs[s], cmap="magma", vmin=0, vmax=vmax, interpolation="nearest")
        axes[1][k].set_title(f"{s} relative error", fontsize=8)
    for ax in axes.ravel():
        ax.axis("off")
    fig.suptitle(f"{result['scene']}, {result['mode']} (error maps on one scale)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pbrt", default="build/pbrt-v4/bin/pbrt")
    ap.add_argument("--table", default="build/pbrt-v4/lattice.tbl", help="for the table-reading aligned modes")
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "..", "integrations", "pbrt-v4", "scenes"))
    ap.add_argument("--out", default="bench/results/pbrt_joint")
    ap.add_argument("--variants", default=",".join(f"{s}:{m}" for s in SCENES for m in MODES),
                    help="scene:mode,... (mode: direct or path5)")
    ap.add_argument("--samplers", default="zsobol,sobol,joint")
    ap.add_argument("--subject", default="joint")
    ap.add_argument("--spp", default="16,64,256,1024")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--res", type=int, default=160)
    ap.add_argument("--ref-factor", type=int, default=16)
    ap.add_argument("--ref-spp", type=int, default=0,
                    help="the reference's spp instead (at least 16x the highest): a rerun of some spp "
                         "against the references of a larger run")
    ap.add_argument("--merge", action="store_true",
                    help="add this run's samplers at this run's spp to the tables already in --out (same "
                         "scenes and reference), replacing what they had for those samplers at those spp; the "
                         "other samplers' runs (and their times) stay")
    ap.add_argument("--retime", metavar="OLD_PBRT", default="",
                    help="re-measure only the frame times of --samplers at --spp in the tables already in "
                         "--out (every sampler in turn, seed by seed, as a full run times them) and keep their "
                         "errors: for a change to a sampler's speed that leaves its images as they were. "
                         "OLD_PBRT is the binary the tables were measured with; each alignset sampler's seed-1 "
                         "render at each spp must be byte for byte OLD_PBRT's, or the run stops")
    ap.add_argument("--floor", action="store_true",
                    help="measure the floor too (the module's docstring): two zsobol renders more at each spp")
    ap.add_argument("--add-floor", action="store_true",
                    help="measure only the floor at --spp and add it to the tables already in --out, against "
                         "each table's own reference (from --ref-cache, or rendered again: the same image)")
    ap.add_argument("--edge-tau", type=float, default=0.03)
    ap.add_argument("--ref-cache", default="build/pbrt-v4/references",
                    help="keeps each reference, keyed by the scene's text, resolution and spp ('' for none)")
    ap.add_argument("--image-spp", type=int, default=256)
    ap.add_argument("--summary-only", action="store_true", help="rewrite summary.md from the tables in --out")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    args = ap.parse_args()
    args.spp = [int(x) for x in args.spp.split(",")]
    args.samplers = args.samplers.split(",")
    for s in args.samplers:
        if s not in SAMPLERS:
            ap.error(f"unknown sampler {s}; known: {', '.join(SAMPLERS)}")
    if args.ref_spp and args.ref_spp < 16 * max(args.spp):
        ap.error("--ref-spp must be at least 16 times the highest --spp")
    if args.seeds < 2:
        ap.error("--seeds must be at least 2 (a standard error needs two)")
    os.makedirs(args.out, exist_ok=True)
    if args.summary_only:
        summary(args.out, args.subject)
        return 0
    t0 = time.monotonic()

    def log(msg):
        print(f"[{time.monotonic() - t0:7.0f} s] {msg}", flush=True)

    with tempfile.TemporaryDirectory() as work:
        r = Renderer(os.path.abspath(args.pbrt), args.res, work, args.threads, os.path.abspath(args.table))
        if args.add_floor:
            for v in args.variants.split(","):
                scene, mode = (v.split(":") + ["direct"])[:2]
                measure_floor(r, os.path.abspath(args.scenes), scene, mode, args, log)
            summary(args.out, args.subject)
            log(f"wrote {args.out}/summary.md")
            return 0
        if args.retime:
            old = Renderer(os.path.abspath(args.retime), args.res, work, args.threads, os.path.abspath(args.table))
            old.count = 1 << 20  # its own file names
            for v in args.variants.split(","):
                scene, mode = (v.split(":") + ["direct"])[:2]
                retime(r, old, os.path.abspath(args.scenes), scene, mode, args, log)
            summary(args.out, args.subject)
            log(f"wrote {args.out}/summary.md")
            return 0
        for v in args.variants.split(","):
            scene, mode = (v.split(":") + ["direct"])[:2]
            if mode not in MODES:
                ap.error(f"mode {mode} of {v}: one of {', '.join(MODES)}")
            result, images = measure(r, os.path.abspath(args.scenes), scene, mode, args, log)
            name = f"{scene}_{mode}"
            old = os.path.join(args.out, name + ".json")
            if args.merge and os.path.exists(old):
                with open(old) as f:
                    before = json.load(f)
                if before["ref_spp"] != result["ref_spp"] or before["edge_pixels"] != result["edge_pixels"]:
                    raise RuntimeError(f"{old}: another reference; --merge needs the same (--ref-spp {before['ref_spp']})")
                order = BASELINES + [x for x in args.samplers if x not in BASELINES]
                kept = [x for x in before["runs"] if x["spp"] not in args.spp or x["sampler"] not in args.samplers]
                result["runs"] = sorted(kept + result["runs"],
                                        key=lambda x: (x["spp"], order.index(x["sampler"])
                                                       if x["sampler"] in order else 99))
                measured, result["floors"] = result.get("floors", []), before.get("floors", [])
                add_floors(result, measured)
                if not result["floors"]:
                    del result["floors"]
            write_table(args, name, result)
            wrote = "json,md"
            if not (args.merge and args.image_spp not in args.spp):  # a merge at other spp keeps the figure
                figure(result, images, os.path.join(args.out, name + ".png"), args.image_spp, args.samplers)
                wrote += ",png"
            log(f"{name}: wrote {args.out}/{name}.{{{wrote}}}")
    if not summary(args.out, args.subject):
        log(f"no summary: {args.out} has no run of {args.subject}")
    else:
        log(f"wrote {args.out}/summary.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
