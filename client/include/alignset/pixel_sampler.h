#pragma once

// The per-pixel recipe of a renderer that uses aligned sets, as the
// renderer in render/ follows it (render/pixel_samplers.cc, class Aligned,
// and render/set_fetch.cc):
//
//  1. Direction. Find the pixel's dominant direction(s) θ (degrees, the
//     normal of the discontinuity edge): from the scene's geometry, or
//     estimated from a low-spp pre-pass of the pixel
//     (ServiceClient::EstimateDirection).
//  2. Key. ChooseSet (<alignset/set_choice.h>) maps them, under an
//     AlignedPolicy, to the set the pixel reads, in the whole degrees a
//     server serves: one direction, two directions (a 4-direction set with
//     the axes), or a fallback sampler.
//  3. Set. RequestFor turns the choice into the SetRequest to ask for
//     (ServiceClient::GetAlignedSet / GetAlignedSets, <alignset/client.h>),
//     of the construction the renderer wants ("" the optimized sets,
//     "lattice", "tent-lattice", "net"). Every pixel with the same choice
//     reads the same set, so fetch each distinct request once, before
//     rendering.
//  4. Shift. PixelPoints gives a pixel its own randomization of that set,
//     with the shift PixelShift(seed, x, y) (<alignset/pixel_shift.h>): an
//     optimized set or a net is shifted on the torus (ShiftPoint), which
//     keeps its spectrum at every integer frequency while neighbouring
//     pixels' errors no longer repeat one another; a lattice or tent-lattice
//     is rebuilt from its generator under that shift (ShiftedLatticePoints,
//     <alignset/lattice_points.h>), because a tent-lattice's shift must come
//     before the fold, which shifting the served points cannot do. There is
//     no per-pixel realization: a realization (SetRequest::realization) is
//     another set, chosen per request.
//
// The sets are those of Werner, Hanika and Dachsbacher, "Optimized and
// Aligned Anisotropic Monte Carlo Sampling Patterns". Header-only.

#include <alignset/client.h>
#include <alignset/lattice_points.h>
#include <alignset/pixel_shift.h>
#include <alignset/set_choice.h>

#include <cstdint>
#include <optional>
#include <string>

namespace alignset {

// The request for a choice's set of N points made by `construction`
// (SetRequest::construction; "" the server's default, the optimized sets);
// none for kFallback.
inline std::optional<SetRequest> RequestFor(const SetChoice& c, uint32_t n,
                                            const std::string& construction = "") {
  SetRequest r;
  r.n = n;
  r.construction = construction;
  switch (c.kind) {
    case SetChoice::Kind::kFallback:
      return std::nullopt;
    case SetChoice::Kind::kOne:
      r.directions_deg = {static_cast<double>(c.a)};
      return r;
    case SetChoice::Kind::kTwo:
      r.directions_deg = {static_cast<double>(c.a), static_cast<double>(c.b)};
      return r;
  }
  return std::nullopt;
}

// A pixel's own points of a served set under `shift` (PixelShift): a lattice
// or tent-lattice rebuilt from its generator with the shift before the fold,
// any other set shifted on the torus. Every uniform shift leaves the
// estimate unbiased. A lattice from a server too old to tell its generator
// (lattice_generator 0) is shifted on the torus too: still unbiased, but a
// tent-lattice then integrates smooth non-periodic shading only about as
// well as Owen-Sobol.
inline PointSet PixelPoints(const AlignedSet& set, Point2 shift) {
  const SetInfo& info = set.info;
  const bool lattice = info.construction == "lattice" || info.construction == "tent-lattice";
  if (lattice && info.lattice_generator != 0 && set.points.size() == info.n) {
    return ShiftedLatticePoints(info.n, info.lattice_generator, shift,
                                info.construction == "tent-lattice");
  }
  PointSet points;
  points.reserve(set.points.size());
  for (const Point2& p : set.points) points.push_back(ShiftPoint(p, shift));
  return points;
}

}  // namespace alignset
