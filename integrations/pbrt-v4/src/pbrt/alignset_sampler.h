// alignset's "aligned" sampler for pbrt-v4 (integrations/pbrt-v4; Apache-2.0
// as pbrt is). Added to pbrt's Sampler by aligned-sampler.patch.
//
// A pixel's T = pixelsamples samples are a pre-pass of M (T / 4 unless
// "prepasssamples" says) and N = T - M main samples, every one of them in
// the image. The pre-pass is one wave of pbrt's render loop of its own; the
// integrator hands each pre-pass sample's luminance back (RecordSample),
// and at a pixel's first main sample the sampler reads the pre-pass values
// of the pixel and its neighbours through alignset's sampler library
// (<alignset/aligned_sampler.h>) into a plan per aligned dimension:
//  - the pixel's film sample (GetPixel2D): the image-plane footprint, where
//    silhouettes and texture edges lie;
//  - the first light sample (the 2-D Get2D at "lightdimension"): every
//    pixel's square over one area light, where shadow edges lie.
// Each plan reads the aligned set for its direction from a table file that
// `alignset export` wrote (or N Owen-scrambled Sobol points where there is
// no direction). Every other dimension is padded Owen-scrambled Sobol (as
// pbrt's "paddedsobol"), and the two aligned dimensions are paired through a
// random permutation, so no dimension's points correlate with another's.
// The samples' film weights (pre-pass M^1.5 / (M^1.5 + 2 N^1.5) in all,
// the main samples the rest) make the pixel alignset's unbiased estimate.
//
// The declaration stays small and stable (pbrt's base/sampler.h is included
// everywhere); the work is in alignset_sampler.cpp.

#ifndef PBRT_ALIGNSET_SAMPLER_H
#define PBRT_ALIGNSET_SAMPLER_H

#include <pbrt/pbrt.h>

#include <pbrt/base/sampler.h>
#include <pbrt/util/vecmath.h>

#include <memory>
#include <string>

namespace pbrt {

class Camera;

class AlignedSampler {
  public:
    static constexpr const char *Name() { return "AlignedSampler"; }
    static AlignedSampler *Create(const ParameterDictionary &parameters,
                                  Point2i fullResolution, const FileLoc *loc,
                                  Allocator alloc);

    // One per render: the table, alignset's samplers, the pre-pass values and
    // the pixels' plans. A clone shares it.
    struct Shared;
    // One per clone (a thread): the current pixel's points and the library's
    // scratch.
    struct Local;

    explicit AlignedSampler(std::shared_ptr<Shared> shared);
    AlignedSampler(const AlignedSampler &other);
    AlignedSampler &operator=(const AlignedSampler &) = delete;
    ~AlignedSampler();

    int SamplesPerPixel() const;
    // M: the pre-pass samples of every pixel (sample indices [0, M)).
    int PrepassSamples() const;
    // The integrator's calls: the pixels rendered and the camera (before the
    // first sample), and each sample's luminance once traced; returns the
    // sample's weight.
    void StartRender(Bounds2i pixelBounds, const Camera &camera);
    Float RecordSample(Point2i pPixel, int sampleIndex, Float luminance);

    void StartPixelSample(Point2i p, int sampleIndex, int dimension = 0);
    Float Get1D();
    Point2f Get2D();
    Point2f GetPixel2D();

    Sampler Clone(Allocator alloc);
    std::string ToString() const;

  private:
    std::shared_ptr<Shared> shared;
    std::unique_ptr<Local> local;
};

}  // namespace pbrt

#endif  // PBRT_ALIGNSET_SAMPLER_H
