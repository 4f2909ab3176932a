#!/usr/bin/python3
"""pbrt-v4 with alignset's "aligned" sampler (integrations/pbrt-v4), on a tiny
scene of silhouettes (tests/pbrt/tiny_edges.pbrt), with pbrt's own spectral
rendering:

 1. unbiased: on four edge pixels, the mean over 48 seeds of the aligned
    sampler's luminance lies within 3 standard errors of a high-spp reference;
 2. better: on the scene's edge pixels (read off the reference alone), its
    MSE over seeds is below zsobol's (pbrt's default) at the same samples a
    pixel, every sample counted;
 3. bad input gets pbrt's error, never a crash or an image: a table without
    the N the sample count needs, a corrupt table, a missing table, a sample
    count below the sampler's least.

and its joint lattice (align "joint") on a tiny soft-shadow scene
(tests/pbrt/tiny_penumbra.pbrt, most pixels a penumbra):

 4. unbiased as in 1., at 64 spp;
 5. better: its edge-pixel MSE at 256 spp below both zsobol's and sobol's
    (pbrt's best on edge pixels), 12 seeds each;
 6. bad input gets pbrt's error: dimensions it cannot serve, a repeated
    dimension, one sample a pixel, a pre-pass asked of a mode without one;
 7. the camera decides the default's dimensions: with a pinhole the lattice
    is the default's, with a thin lens the lens and time join it (byte for
    byte the lattices "jointdimensions" names);
 8. randomize "jitter" gives another image than the shift's, unbiased;
 9. the benchmark's floor: with the sampler's seed fixed, pbrt's --seed
    changes nothing on a diffuse scene and, with a coated floor, changes the
    image by a walk whose variance falls as 1/N.

  test_pbrt_sampler.py PBRT MAKE_TABLE_SH BUILD_DIR

Exits 77 (CTest: skipped) with the reason when PBRT does not exist: no
pbrt-v4 source was given to scripts/test.sh (ALIGNSET_PBRT_SOURCE).
"""

import os
import subprocess
import sys
import tempfile

import numpy as np

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
EDGES = os.path.join(HERE, "tiny_edges.pbrt")
PENUMBRA = os.path.join(HERE, "tiny_penumbra.pbrt")
# The benchmark's PFM reader and edge rule (bench/pbrt_samplers.py).
sys.path.insert(0, os.path.join(HERE, "..", "..", "bench"))
from pbrt_samplers import luminance, neighbour_jump, read_pfm  # noqa: E402


class Pbrt:
    def __init__(self, binary, work, scene):
        self.binary, self.work, self.scene, self.count = binary, work, scene, 0
        self.flags = []

    def run(self, sampler_line, spp, seed, filt="box"):
        self.count += 1
        out = os.path.join(self.work, f"r{self.count}.pfm")
        body = "".join(l for l in open(self.scene) if not l.startswith(("Film", "Sampler", "PixelFilter")))
        scene = os.path.join(self.work, f"r{self.count}.pbrt")
        with open(scene, "w") as f:
            f.write(f'{sampler_line}\n'
                    f'PixelFilter "{filt}"\n'
                    f'Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ] "string filename" [ "{out}" ]\n'
                    + body)
        p = subprocess.run([self.binary, "--quiet", "--nthreads", "2", "--spp", str(spp), "--seed", str(seed)]
                           + self.flags + [scene], capture_output=True, text=True)
        return p, (read_pfm(out) if p.returncode == 0 else None)

    def image(self, sampler_line, spp, seed):
        p, img = self.run(sampler_line, spp, seed)
        if p.returncode != 0:
            raise AssertionError(f"pbrt failed ({p.returncode}): {p.stderr[-600:]}")
        return img


class Reference:
    """A scene's reference: two zsobol halves of 16384 spp under seeds no
    measured render uses, their mean's luminance, jumps and edge pixels."""

    def __init__(self, pbrt):
        self.a = pbrt.image('Sampler "zsobol"', 16384, 9001)
        self.b = pbrt.image('Sampler "zsobol"', 16384, 9002)
        self.image = 0.5 * (self.a + self.b)
        self.y = luminance(self.image)
        self.jump = neighbour_jump(self.y)
        self.edge = self.jump > 0.03 * np.percentile(self.y, 99)

    def mixed(self):
        """Edge pixels with an edge through them (a value between the two
        sides'), not a black shadow beside a lit one."""
        p99 = np.percentile(self.y, 99)
        return self.edge & (self.y > 0.2 * p99) & (self.y < 0.8 * p99)

    def largest_deviation(self, means, label):
        """Over the four mixed pixels of the largest jumps: the largest
        |mean over seeds - reference| in standard errors (the seeds' and the
        reference's own, from its two halves)."""
        seeds = len(means)
        order = np.argsort(np.where(self.mixed(), self.jump, -1).ravel())[::-1][:4]
        worst = 0.0
        for flat in order:
            py, px = divmod(int(flat), self.y.shape[1])
            vals = means[:, py, px]
            se = vals.std(ddof=1) / np.sqrt(seeds)
            ref_se = abs(float(luminance(self.a[py, px] - self.b[py, px]))) / 2.0
            z = abs(vals.mean() - float(self.y[py, px])) / np.sqrt(se ** 2 + ref_se ** 2 + 1e-30)
            print(f"{label}, pixel ({px}, {py}): mean {vals.mean():.5f}, reference {float(self.y[py, px]):.5f}, "
                  f"{z:.2f} standard errors")
            worst = max(worst, float(z))
        return worst

    def edge_mse(self, images):
        """The mean over images of each one's MSE on the edge pixels."""
        return float(np.mean([((img - self.image) ** 2).mean(axis=2)[self.edge].mean() for img in images]))


def penumbra_variant(pbrt_bin, work, name, line, replacement):
    """tests/pbrt/tiny_penumbra.pbrt with one line replaced, as a Pbrt."""
    with open(PENUMBRA) as f:
        text = f.read()
    assert line in text, f"tiny_penumbra.pbrt has no {line!r} any more: update this test"
    path = os.path.join(work, f"tiny_penumbra_{name}.pbrt")
    with open(path, "w") as g:
        g.write(text.replace(line, replacement))
    return Pbrt(pbrt_bin, work, path)


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    pbrt_bin, make_table, build_dir = sys.argv[1:]
    if not os.path.exists(pbrt_bin):
        print(f"SKIPPED: no pbrt-v4 built at {pbrt_bin}: scripts/test.sh builds it when given a "
              f"pbrt-v4 source folder (ALIGNSET_PBRT_SOURCE=/path/to/pbrt-v4), as .ci/run does")
        return SKIP
    failures = []

    def check(ok, what):
        print(("PASS " if ok else "FAIL ") + what, flush=True)
        if not ok:
            failures.append(what)

    with tempfile.TemporaryDirectory() as work:
        table = os.path.join(work, "lattice.tbl")
        subprocess.run(["bash", make_table, table, "48,192", build_dir], check=True, capture_output=True)
        pbrt = Pbrt(pbrt_bin, work, EDGES)
        aligned = f'Sampler "aligned" "string table" [ "{table}" ]'
        zsobol = 'Sampler "zsobol"'

        # The reference: two halves under seeds no measured render uses.
        r = Reference(pbrt)
        edge = r.edge
        print(f"edge pixels: {int(edge.sum())} of {edge.size}")
        check(edge.sum() >= 40, f"the scene has edge pixels to judge ({int(edge.sum())} >= 40)")

        # 1. Unbiased: 48 seeds at 64 spp (a pre-pass of 16, 48 main
        # samples: the sampler's smallest count); on the luminance of the four
        # mixed edge pixels of the largest jumps, the mean within 3 standard errors
        # of the reference (the reference's own, from its two halves, added).
        # The seeds are fixed, so the test is deterministic for a build.
        seeds = 48
        means = np.array([luminance(pbrt.image(aligned, 64, s)) for s in range(1, seeds + 1)])
        check(r.mixed().sum() >= 4, f"the scene has mixed edge pixels ({int(r.mixed().sum())} >= 4)")
        worst = r.largest_deviation(means, "aligned")
        check(worst < 3.0, f"aligned's mean over {seeds} seeds within 3 standard errors of the reference "
                           f"on 4 edge pixels (largest {worst:.2f})")

        # 2. Better than zsobol on the edge pixels at 256 spp, every sample counted.
        mse_aligned = r.edge_mse([pbrt.image(aligned, 256, s) for s in range(1, 13)])
        mse_zsobol = r.edge_mse([pbrt.image(zsobol, 256, s) for s in range(1, 13)])
        print(f"edge-pixel MSE at 256 spp over 12 seeds: aligned {mse_aligned:.3e}, zsobol {mse_zsobol:.3e}, "
              f"ratio {mse_zsobol / mse_aligned:.2f}")
        check(mse_aligned < mse_zsobol, "aligned's edge-pixel MSE below zsobol's at 256 spp")

        # 3. Bad input: pbrt's own error (exit status 1), a message naming the
        # problem, no image.
        def refused(sampler_line, spp, needle, what, renderer=pbrt):
            p, img = renderer.run(sampler_line, spp, 1)
            ok = p.returncode == 1 and img is None and needle in p.stderr
            check(ok, f"{what}: exit {p.returncode}, message names it" + ("" if ok else f": {p.stderr[-400:]!r}"))

        refused(aligned, 128, "N = 48, 192", "a table without the N of 128 spp (96): the table's N named")
        with open(table, "rb") as f:
            data = bytearray(f.read())
        data[len(data) // 2] ^= 0x10
        corrupt = os.path.join(work, "corrupt.tbl")
        with open(corrupt, "wb") as f:
            f.write(data)
        refused(f'Sampler "aligned" "string table" [ "{corrupt}" ]', 256, "checksum", "a corrupt table")
        refused(f'Sampler "aligned" "string table" [ "{work}/none.tbl" ]', 256, "none.tbl", "a missing table")
        refused(aligned, 32, "at least 16", "32 spp (a pre-pass of 8)")
        refused('Sampler "aligned"', 256, "table", "no table named")
        refused(f'{aligned} "string align" [ "sideways" ]', 256, "film+light", "an unknown \"align\"")

        # 4-6. The joint lattice on the penumbra scene.
        pen = Pbrt(pbrt_bin, work, PENUMBRA)
        joint = 'Sampler "aligned" "string align" [ "joint" ]'
        r = Reference(pen)
        edge = r.edge
        print(f"penumbra scene: edge pixels: {int(edge.sum())} of {edge.size}")
        check(edge.sum() >= 200, f"the penumbra scene has edge pixels to judge ({int(edge.sum())} >= 200)")
        seeds = 48

        def check_unbiased(line, label):
            means = np.array([luminance(pen.image(line, 64, s)) for s in range(1, seeds + 1)])
            worst = r.largest_deviation(means, label)
            check(worst < 3.0, f"{label}: the mean over {seeds} seeds within 3 standard errors of the "
                               f"reference on 4 penumbra pixels (largest {worst:.2f})")

        check(r.mixed().sum() >= 4, f"the penumbra scene has mixed edge pixels ({int(r.mixed().sum())} >= 4)")
        check_unbiased(joint, "joint")

        mse = {name: r.edge_mse([pen.image(line, 256, s) for s in range(1, 13)])
               for name, line in (("joint", joint), ("zsobol", zsobol), ("sobol", 'Sampler "sobol"'))}
        print("penumbra edge-pixel MSE at 256 spp over 12 seeds: " +
              ", ".join(f"{k} {v:.3e}" for k, v in mse.items()) +
              f"; zsobol / joint {mse['zsobol'] / mse['joint']:.2f}, sobol / joint {mse['sobol'] / mse['joint']:.2f}")
        check(mse["joint"] < mse["zsobol"], "joint's penumbra edge MSE below zsobol's at 256 spp")
        check(mse["joint"] < mse["sobol"], "joint's penumbra edge MSE below sobol's at 256 spp")

        for params, spp, needle, what in (
                (' "integer jointdimensions" [ 5 99 ]', 64, "99", "a dimension pbrt's sampler cannot serve"),
                (' "integer jointdimensions" [ 5 5 ]', 64, "twice", "a dimension listed twice"),
                ("", 1, "at least 2", "one sample a pixel"),
                (' "integer prepasssamples" [ 16 ]', 64, "pre-pass", "a pre-pass asked of joint"),
                (' "string randomize" [ "owen" ]', 64, "owen", "a randomization joint does not have"),
                (' "integer tentdimensions" [ 11 ]', 64, "11", "a tent on a dimension not in the lattice"),
                (' "integer tentdimensions" [ 0 ]', 64, "wavelength", "a tent on the folded wavelength"),
                (' "string randomize" [ "tent" ] "integer tentdimensions" [ 8 ]', 64, "tents them all",
                 "a tent both everywhere and on some dimensions")):
            refused(joint + params, spp, needle, what, renderer=pen)

        # 7. The camera decides the default's dimensions: with a pinhole the
        # lattice is the one "jointdimensions" [ 5 6 0 8 9 7 4 ] names; with a
        # thin lens, the lens (2, 3) and time (1) right after the film. Byte
        # for byte, so each is the named lattice and not merely close to it.
        named_default = joint + ' "integer jointdimensions" [ 5 6 0 8 9 7 4 ]'
        named_lens = joint + ' "integer jointdimensions" [ 2 3 1 5 6 0 8 9 7 4 ]'
        pen_joint = pen.image(joint, 64, 3)
        check(np.array_equal(pen_joint, pen.image(named_default, 64, 3)),
              "a pinhole camera: joint's lattice is the default's")
        lens = penumbra_variant(pbrt_bin, work, "lens", 'Camera "perspective" "float fov" [ 32 ]',
                                'Camera "perspective" "float fov" [ 32 ] "float lensradius" [ 0.05 ] '
                                '"float focaldistance" [ 1.2 ]')
        lens_joint = lens.image(joint, 64, 3)
        check(np.array_equal(lens_joint, lens.image(named_lens, 64, 3)),
              "a thin lens: the lens and time join joint's lattice after the film")
        check(not np.array_equal(lens_joint, lens.image(named_default, 64, 3)),
              "a thin lens: joint's lattice is not the pinhole's")

        # 8. randomize "jitter" reaches the library (another image than the
        # shift's) and stays unbiased in pbrt.
        jitter = joint + ' "string randomize" [ "jitter" ]'
        check(not np.array_equal(pen.image(jitter, 64, 3), pen_joint),
              "randomize \"jitter\": another image than the shift's")
        check_unbiased(jitter, "joint, jittered")

        # 9. The benchmark's floor (bench/pbrt_equal_time.py --floor) rests on
        # pbrt's --seed reaching only the layered BSDFs' random walk once the
        # sampler's seed is fixed: the same image without a layered
        # material, another with one, and a walk's variance that falls as
        # 1/N (half the two images' squared difference, 64 to 256 spp).
        fixed = 'Sampler "zsobol" "integer seed" [ 77 ]'
        check(np.array_equal(pen.image(fixed, 64, 11), pen.image(fixed, 64, 12)),
              "the floor: --seed changes nothing but the layered walk (a diffuse scene, sampler seed fixed)")
        coated = penumbra_variant(pbrt_bin, work, "coated", 'Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]',
                                  'Material "coateddiffuse" "rgb reflectance" [ 0.7 0.7 0.7 ] '
                                  '"float roughness" [ 0.1 ]')
        walk = {}
        for spp in (64, 256):
            a, b = coated.image(fixed, spp, 11), coated.image(fixed, spp, 12)
            walk[spp] = float((((a - b) ** 2).mean(axis=2) / 2).mean())
        print(f"the floor on the coated floor: {walk[64]:.3e} at 64 spp, {walk[256]:.3e} at 256 "
              f"({walk[64] / max(walk[256], 1e-30):.2f}x)")
        check(walk[64] > 0 and 2.5 < walk[64] / max(walk[256], 1e-30) < 6.5,
              "the floor: a layered material's walk changes with --seed and its variance falls as 1/N")

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
