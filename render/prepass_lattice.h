#pragma once

#include <cstdint>

#include "core/util/point_set.h"

namespace alignset::render {

// The lattice pre-pass (suffix "l" on a scattered pre-pass, `nedges64s2l`),
// the sampler library's (PrepassLatticePointsInto, <alignset/prepass_fit.h>):
// the pixel's M pre-pass samples are the M-point rank-1 lattice of
// generator Rank1Generator(M) (core/sampling/rank1_lattice.h) under a
// uniform shift drawn from the pixel's seed, instead of M Owen-scrambled
// Sobol points.
//
// Why: the edge-line fit places a line through the midpoints of neighbouring
// samples whose values jump, and a lattice's samples are spread more evenly
// than Owen-Sobol points (no two closer than its minimum distance), so the
// crossings sit more evenly along an edge. With the same fit, stack and
// aligned lattices the rendered edge MSE was 0.95-0.99x the Owen-Sobol
// pre-pass's on the means at 256 + 64 and 1024 + 256 (scene seeds 1-18)
// and on the shared domain at 4096 + 256; on footprints at 4096 + 256
// single scenes moved by up to 27% either way, so `auto` takes it up to
// N = 1024 and on a shared domain (AutoPrepass; docs/rendering.md,
// "Every sample counted").
//
// Its mean is an unbiased estimate of the pixel (the shift is uniform), so a
// pixel with a direction reuses it with the count weights as it would an
// Owen-Sobol pre-pass (render/prepass_reuse.h). It is no net, so there is
// no sequence to continue on a pixel without a direction: such a pixel
// takes the sampler's own Owen-Sobol points alone (a 64-point lattice on
// smooth shading that is not periodic on the pixel converges like n^-2,
// a net like n^-3, and would add next to nothing at its weight).
//
// Measured and not kept: lifting the pre-pass into the pixel's final
// lattice (the T = N + M point lattices of generator g0 + k M contain the
// pre-pass's points, so all M samples could count at full weight, the best
// of the four coprime generators of 320 for the pixel's directions taken):
// on scene seeds 1-12 at 256 + 64 its edge MSE was 11% (antialias) and 8%
// (shadow) above the aligned 256-point lattice after the same lattice
// pre-pass, one shadow seed 39%: four candidates are too few against the
// search over every generator.
PointSet PrepassLatticePoints(uint32_t m, uint64_t seed);

}  // namespace alignset::render
