#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "core/analysis/direction_estimate.h"
#include "core/analysis/patch_spectrum.h"
#include "core/util/status.h"

namespace alignset {

// A pixel's edge direction from scattered samples, located rather than
// seen in the spectrum. The spectral estimator (direction_estimate.h) needs
// the edge's line energy to stand above the Monte Carlo noise of M random
// samples, which at M = 256 it often does not (bench/direction_accuracy:
// half the steps direction-less, 3° median on the rest). Yet with M samples
// a straight edge is crossed by about sqrt(M) pairs of neighbouring samples
// whose values jump, and the midpoints of those pairs lie within a sample
// spacing of the edge's line; a line through them is accurate to about
// spacing / (length sqrt(crossings)).
//
// 1. Neighbours: pairs of samples closer than neighbour_radius / sqrt(M)
//    (about 8 neighbours each), found through a bucket grid.
// 2. Crossings: the pairs whose values differ by at least jump_fraction of
//    the patch's range (max - min); their midpoints.
// 3. A robust line: candidate lines through two crossings at least a third
//    of the patch apart (a fixed, deterministic choice of candidates), each
//    scored by the crossings within band / sqrt(M) of it; the best refined
//    by total least squares on its inliers (twice).
// 4. Found when at least min_crossings lie on it and they are at least
//    min_share of all crossings; confidence = that share. With `second`,
//    steps 3-4 again on the crossings off the first line (second_min_share
//    of all, and at least min_separation_deg away from the first).
// A constant patch, a smooth one (no pair jumps) and a noisy one (crossings
// on no line) have no dominant direction.
struct EdgeLineOptions {
  double neighbour_radius = 1.6;  // in sample spacings 1/sqrt(M)
  double jump_fraction = 0.35;
  double band = 0.8;              // half-width of a line's inlier band, in spacings
  int min_crossings = 6;
  double min_share = 0.5;
  int candidates = 96;
  bool second = false;
  double second_min_share = 0.25;
  double min_separation_deg = 2.0;
  // A focus box (in the patch's coordinates, inside [0,1]^2): only lines
  // that cross it are candidates. A patch pooled from a pixel and its
  // neighbours (the renderer's nedgesM pre-pass) looks for the edge through
  // the pixel, not for the strongest edge nearby.
  bool focus = false;
  double focus_x0 = 0.0, focus_y0 = 0.0, focus_x1 = 1.0, focus_y1 = 1.0;
};

// INVALID_ARGUMENT for an invalid patch (ValidateSampledPatch) or options
// out of range; a valid patch without an edge is a result whose first lobe
// is kNoDominantDirection with the reason. theta_deg is the edge's normal
// (the spectral convention), kappa is 0 (no fit of a distribution).
StatusOr<DirectionEstimate> EstimateEdgeLines(const SampledPatch& patch,
                                              const EdgeLineOptions& options = {});

// The inset of EstimateEdgeLinesPooled's focus box, in sample spacings
// (1/sqrt(M) for M samples per pixel). A crossing's midpoint between a
// sample inside the pixel and one in the neighbour can lie inside the pixel
// though the edge does not: without an inset smooth pixels beside an edge
// were given directions (on antialias, N = 256, their squared error 3.7x
// Owen-Sobol's at the same N). A whole spacing lost the edges that run near
// the pixel's border. At half a spacing 2 of 80781 smooth pixels took a
// direction (their error unchanged), and aligned lattices' edge error fell
// 4-12% at N = 256 on each of six scene seeds and 0.5-13% at 1024 and 4096
// (docs/rendering.md).
inline constexpr double kPooledFocusInset = 0.5;

// A pixel's fit from its own samples and its neighbours' (the renderer's
// nedgesM pre-pass): an edge runs on into the next pixel, so its line is
// better placed by the crossings on either side. `pixels` holds the 3 x 3
// block row by row, the centre at [4], each patch in its own pixel's
// [0,1]^2 (nullptr where the image ends); the samples within `margin`
// pixel widths of the centre pixel are scaled onto the unit square, and
// the options gain a focus box on the centre pixel, inset by
// kPooledFocusInset sample spacings. INVALID_ARGUMENT for a missing centre,
// a margin outside (0, 1] or what EstimateEdgeLines refuses.
StatusOr<DirectionEstimate> EstimateEdgeLinesPooled(const std::array<const SampledPatch*, 9>& pixels,
                                                    double margin, const EdgeLineOptions& options = {});

// A pixel's fit from its own samples and its neighbours' where every pixel
// integrates over the same domain (a light source's square, a lens): the
// neighbours see the same edges, moved a little by their own position, not
// the edge's continuation beside the pixel (which EstimateEdgeLinesPooled
// reads). Each of the 9 patches (the centre at [4], nullptr where the image
// ends, each over the shared [0,1]^2, every one with the centre's sample
// count) gives its own crossings; a candidate direction is scored by the
// crossings within the band of one line per patch, all lines parallel, each
// at its patch's best offset, and must rest on at least two of the centre's
// own crossings; the refinement pools each patch's scatter about its own
// inliers' centroid. Steps 3-4 and the second line as in EstimateEdgeLines,
// the shares over all patches' crossings; with a second line (a corner),
// the first line's direction is then fitted again on the crossings off the
// second line's band, since the vertex's crossings lie in both bands and
// pull a half-line's fit towards the other edge. INVALID_ARGUMENT for a
// missing centre, an invalid patch or options out of range.
StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::array<const SampledPatch*, 9>& pixels,
                                                     const EdgeLineOptions& options = {});
// The same over a larger odd square block (5 x 5, ...), row by row, the
// centre in the middle.
StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::vector<const SampledPatch*>& pixels,
                                                     const EdgeLineOptions& options = {});

// Steps 1-2 of one patch: its crossings. A stacked fit reads every pixel of
// its block, so a renderer that fits every pixel of an image finds each
// pixel's crossings once and hands them to the fit of each block the pixel
// is in ((2R + 1)^2 of them) instead of finding them again in each.
struct PatchCrossings {
  std::vector<Point2> midpoints;  // empty for a constant patch
  size_t samples = 0;             // the patch's M
  bool constant = true;
};
// INVALID_ARGUMENT for an invalid patch or options.
StatusOr<PatchCrossings> FindCrossings(const SampledPatch& patch, const EdgeLineOptions& options = {});
// EstimateEdgeLines from the patch's crossings, found with the same
// options: the same estimate, to the last bit (a renderer that also stacks
// the pixel's crossings finds them once). INVALID_ARGUMENT for crossings of
// no samples or options out of range.
StatusOr<DirectionEstimate> EstimateEdgeLines(const PatchCrossings& crossings,
                                              const EdgeLineOptions& options = {});
// EstimateEdgeLinesStacked from the block's crossings, found with the same
// options: the same estimate, to the last bit.
StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::vector<const PatchCrossings*>& pixels,
                                                     const EdgeLineOptions& options = {});

// The working memory of the fits, for a caller that fits many patches (a
// renderer's pixels): with one kept per thread and the results written into
// the caller's own PatchCrossings and DirectionEstimate, a fit allocates
// nothing once the buffers have grown to the largest patch seen (a lobe's
// reason is written into the string it already holds). The same estimates,
// to the last bit, as the calls above, which run these with a scratch of
// their own.
class EdgeLineScratch {
 public:
  EdgeLineScratch();
  ~EdgeLineScratch();
  EdgeLineScratch(EdgeLineScratch&&) noexcept;
  EdgeLineScratch& operator=(EdgeLineScratch&&) noexcept;
  // Grows every buffer to hold patches of `points` samples with `crossings`
  // crossings in all, over `patches` stacked patches, so that fits up to
  // that size allocate nothing from the first on.
  void Reserve(size_t points, size_t crossings, size_t patches);
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};
Status FindCrossings(const SampledPatch& patch, const EdgeLineOptions& options, EdgeLineScratch& scratch,
                     PatchCrossings* out);
Status EstimateEdgeLines(const SampledPatch& patch, const EdgeLineOptions& options, EdgeLineScratch& scratch,
                         DirectionEstimate* out);
Status EstimateEdgeLines(const PatchCrossings& crossings, const EdgeLineOptions& options, EdgeLineScratch& scratch,
                         DirectionEstimate* out);
Status EstimateEdgeLinesPooled(const std::array<const SampledPatch*, 9>& pixels, double margin,
                               const EdgeLineOptions& options, EdgeLineScratch& scratch, DirectionEstimate* out);
Status EstimateEdgeLinesStacked(std::span<const PatchCrossings* const> pixels, const EdgeLineOptions& options,
                                EdgeLineScratch& scratch, DirectionEstimate* out);

}  // namespace alignset
