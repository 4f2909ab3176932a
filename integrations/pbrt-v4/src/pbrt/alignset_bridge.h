// The aligned sampler's side of alignset's sampler library, behind a C++17
// interface: pbrt-v4's headers do not compile as C++20 (aggregates with
// user-declared constructors) and alignset's do not compile as C++17
// (std::span), so no file includes both. alignset_bridge.cpp (C++20) holds
// the library's samplers, the table and the pixels' plans;
// alignset_sampler.cpp (C++17, pbrt's) calls it.

#ifndef PBRT_ALIGNSET_BRIDGE_H
#define PBRT_ALIGNSET_BRIDGE_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pbrt_alignset {

struct Point {
    double x = 0, y = 0;
};

// The two dimensions the sampler aligns: the film sample (each pixel's own
// footprint) and the light sample (one square shared by every pixel).
enum Domain { kFilm = 0, kLight = 1 };

class Planner {
  public:
    struct Config {
        std::string table;         // the table file
        std::string construction;  // its construction to read
        int prepass = 0;           // M
        int main = 0;              // N
        int imageWidth = 0;        // pixels per row (pixel seeds)
        int stackRadius = 0;       // the light's stacked block radius; 0: the library's
        int thirdHarmonic = 1;     // the third coordinate's function has period 1 / this
        uint64_t seed[2] = {0, 0}; // per domain
    };
    // Per thread: the library's buffers and a point buffer.
    struct Scratch;
    // nullptr, with *error naming the problem (the table's own message, or
    // the N it lacks), when the table or the counts cannot serve.
    static std::unique_ptr<Planner> Create(const Config &config, std::string *error);
    ~Planner();

    double PrepassWeight() const;
    int BlockRadius(Domain d) const;
    int BlockSide(Domain d) const;
    static std::unique_ptr<Scratch, void (*)(Scratch *)> NewScratch();

    // Plans for `pixels` pixels, indexed as the caller likes.
    void StartRender(size_t pixels);
    // Pixel (x, y)'s M pre-pass points of a domain.
    void PrepassPoints(Domain d, uint32_t x, uint32_t y, Point *out, Scratch &scratch) const;
    // Plans pixel (x, y) of index `pixel` from its block: BlockSide(d)^2
    // pointers, row by row from (x - R, y - R), each to M pre-pass values in
    // the domain's point order, or nullptr outside the image. Returns the
    // directions found (0, 1 or 2).
    int Plan(Domain d, size_t pixel, uint32_t x, uint32_t y, const double *const *block,
              Scratch &scratch);
    // The planned pixel's N main points.
    void MainPoints(Domain d, size_t pixel, Point *out, Scratch &scratch) const;
    // A third coordinate for the planned pixel's main points where they are
    // a lattice (i (1, g) / N, shifted): the multiplier h of
    // w_i = frac(i h / N + s), chosen so that the 3-D lattice (1, g, h) / N
    // keeps its dual vectors with small third components off the pixel's
    // edge normal and the axes. A smooth 1-D dimension (pbrt's wavelength
    // sample) then pairs with the set without the Monte Carlo-rate cross
    // term that a random pairing of a step and a smooth function leaves.
    // 0 where the pixel's points are not a lattice.
    uint32_t ThirdMultiplier(Domain d, size_t pixel) const;

  private:
    struct Impl;
    explicit Planner(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl;
};

// alignset's joint lattice (<alignset/joint_lattice.h>): one rank-1 lattice
// of N points a pixel over `dimensions` of a camera sample's dimensions,
// shifted per pixel, every other dimension padded by the library. No
// pre-pass and no table: the generator is searched at Create (12 ms at 4096
// samples a pixel, 2.5 s at 65536).
class JointPoints {
  public:
    // nullptr, with *error naming the problem, for an N or a dimension count
    // the library refuses. folds[d]: the library's fold of lattice dimension
    // d (the period 1 / folds[d] of the integrand along it; pbrt's wavelength
    // sample has NSpectrumSamples). tents[d]: lattice dimension d's shift is
    // followed by the tent (the library's JointLattice). jitter: each lattice
    // dimension jittered within its strata instead of shifted.
    static std::unique_ptr<JointPoints> Create(int n, int dimensions, uint64_t seed,
                                               const std::vector<uint32_t> &folds,
                                               const std::vector<bool> &tents, bool jitter,
                                               std::string *error);
    ~JointPoints();
    int Dimensions() const;
    // Dimension d of sample i of pixel `pixel` (y * width + x): a lattice
    // coordinate for d < Dimensions(), the library's padding beyond.
    double Sample(uint64_t pixel, uint32_t i, uint32_t d) const;

    // One pixel's view (the library's JointLatticePixel: the pixel's shifts
    // and scramble keys hashed once, not per value), one per thread. Its
    // values are Sample's.
    class Pixel {
      public:
        Pixel();
        ~Pixel();
        // Points the view at pixel `pixel` of `points` (which outlives it).
        void Reset(const JointPoints &points, uint64_t pixel);
        bool Valid() const;
        uint64_t Index() const;
        double Sample(uint32_t i, uint32_t d);

      private:
        struct Impl;
        std::unique_ptr<Impl> impl;
    };

  private:
    struct Impl;
    explicit JointPoints(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl;
};

}  // namespace pbrt_alignset

#endif  // PBRT_ALIGNSET_BRIDGE_H
