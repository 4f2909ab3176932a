// alignset's "aligned" sampler for pbrt-v4: see alignset_sampler.h.

#include <pbrt/alignset_sampler.h>

#include <pbrt/cameras.h>
#include <pbrt/options.h>
#include <pbrt/paramdict.h>
#include <pbrt/util/check.h>
#include <pbrt/util/error.h>
#include <pbrt/util/file.h>
#include <pbrt/util/hash.h>
#include <pbrt/util/lowdiscrepancy.h>
#include <pbrt/util/math.h>
#include <pbrt/util/print.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/stats.h>

#include "alignset_bridge.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pbrt {

STAT_COUNTER("Aligned sampler/Pixels planned", nPlanned);
STAT_COUNTER("Aligned sampler/Pixels with a film-sample direction", nFilmDirection);
STAT_COUNTER("Aligned sampler/Pixels with a light-sample direction", nLightDirection);

namespace {

// Which of a pixel's 2-D samples take aligned points.
// kJoint: no pre-pass and no table, one joint lattice a pixel over the film
// and the dimensions of "jointdimensions" (alignset's JointLattice).
enum class Aligned { kFilmAndLight, kFilm, kLight, kNone, kJoint };

// The sampler dimensions (as this sampler counts them: GetPixel2D takes
// none) that "jointdimensions" may name, and their default: the first light
// sample (5, 6), the wavelength (0), the first BSDF direction (8, 9) and lobe
// (7), the light choice (4). The film takes the lattice's first two.
constexpr int kJointMaxDimension = 64;
constexpr int kJointDefault[] = {5, 6, 0, 8, 9, 7, 4};
// Where the camera has a lens (depth of field), the default puts its lens
// sample (2, 3) and time (1) right after the film, before kJointDefault, so
// that the film and lens squares are searched together. A pinhole camera
// reads the lens sample and ignores it, so there the lattice keeps
// kJointDefault.
constexpr int kJointLensFirst[] = {2, 3, 1};

constexpr int kPassPrepass = 0, kPassMain = 1;
// The dimension of pbrt's wavelength sample: RayIntegrator::EvaluatePixelSample's
// first Get1D after StartPixelSample.
constexpr int kWavelengthDimension = 0;

}  // namespace

using pbrt_alignset::Planner;
using Point = pbrt_alignset::Point;
using pbrt_alignset::kFilm;
using pbrt_alignset::kLight;

struct AlignedSampler::Shared {
    int samplesPerPixel = 0;
    int prepass = 0;  // M
    int main = 0;     // N
    int seed = 0;
    int lightDimension = 5;
    bool pairWavelength = true;
    Aligned aligned = Aligned::kFilmAndLight;
    std::string tablePath, construction;
    std::unique_ptr<Planner> planner;
    double prepassWeight = 0;  // M^1.5 / (M^1.5 + 2 N^1.5)
    // kJoint: the lattice, and each sampler dimension's lattice dimension
    // (-1: padded by the library).
    std::unique_ptr<pbrt_alignset::JointPoints> joint;
    int jointOf[kJointMaxDimension];
    // kJoint: each padded sampler dimension's library dimension (the library
    // pads dimension A + k, A the lattice dimensions asked for, with its
    // padding's dimension k, so the first padded sampler dimensions get the
    // padding's best).
    int jointPadOf[kJointMaxDimension];
    int jointTents = 0;  // lattice dimensions tented
    // kJoint: no "jointdimensions" given (StartRender may choose the lens's
    // default); "randomize" "tent", or the sampler dimensions of "tentdimensions".
    bool jointDefaultDimensions = false;
    bool jointTentAll = false;
    bool jointJitter = false;
    std::vector<int> jointTented;
    int imageWidth = 0;  // the pixel index is y * imageWidth + x

    // Set by StartRender.
    Bounds2i bounds;
    std::vector<double> values;   // each pixel's M pre-pass luminances, in sample order
    std::vector<uint8_t> planned;  // written by the pixel's own thread only

    bool Joint() const { return aligned == Aligned::kJoint; }
    // Library dimension d of sample i of the pixel `view` is at, below 1.
    static Float JointPoint(pbrt_alignset::JointPoints::Pixel &view, int i, uint32_t d) {
        return std::min(Float(view.Sample(uint32_t(i), d)), OneMinusEpsilon);
    }
    // Sampler dimension `dim` of sample i under kJoint: its lattice dimension,
    // or the library's padding past any lattice dimension.
    Float JointSample(pbrt_alignset::JointPoints::Pixel &view, int i, int dim) const {
        if (dim < kJointMaxDimension)
            return JointPoint(view, i, uint32_t(jointOf[dim] >= 0 ? jointOf[dim] : jointPadOf[dim]));
        // Past kJointMaxDimension every sampler dimension is padded, after
        // the A - 2 of "jointdimensions": A + dim - (A - 2).
        return JointPoint(view, i, uint32_t(dim + 2));
    }
    bool AlignsFilm() const {
        return aligned == Aligned::kFilmAndLight || aligned == Aligned::kFilm;
    }
    bool AlignsLight() const {
        return aligned == Aligned::kFilmAndLight || aligned == Aligned::kLight;
    }
    size_t PixelIndex(Point2i p) const {
        Point2i q = Point2i(p - bounds.pMin);
        return size_t(q.y) * size_t(bounds.pMax.x - bounds.pMin.x) + size_t(q.x);
    }
    // Where pixel p's light sample s of a pass lies among the light set's
    // points: a permutation of the pass, so the film and light points of one
    // sample are independent (both sets are lattices of one generator family).
    uint32_t LightIndex(Point2i p, int pass, int s, int count) const {
        return PermutationElement(uint32_t(s), uint32_t(count),
                                  uint32_t(Hash(p, pass, seed, 0x6c696768)));
    }
};

struct AlignedSampler::Local {
    Point2i pixel{-1, -1};
    int pass = -1;  // the pass the cached points below are of
    int sampleIndex = 0, dimension = 0;
    // The sample's index within its pass, and the pass's sample count.
    int IndexInPass(const Shared &s) const {
        return pass == kPassPrepass ? sampleIndex : sampleIndex - s.prepass;
    }
    int PassCount(const Shared &s) const { return pass == kPassPrepass ? s.prepass : s.main; }
    // kJoint: the library's view of the current pixel (its hashes made once
    // a pixel, not once a value).
    pbrt_alignset::JointPoints::Pixel jointView;
    std::vector<Point> filmPoints, lightPoints;
    // The main pass's wavelength sample as a third lattice coordinate
    // (Planner::ThirdMultiplier) of the film set or, without one, the light
    // set: 0 where neither is a lattice.
    uint32_t third = 0;
    pbrt_alignset::Domain thirdDomain = pbrt_alignset::kFilm;
    double thirdShift = 0;
    std::unique_ptr<Planner::Scratch, void (*)(Planner::Scratch *)> scratch{Planner::NewScratch()};
    std::vector<double> blockValues;
    std::vector<const double *> block;
};

AlignedSampler::AlignedSampler(std::shared_ptr<Shared> shared)
    : shared(std::move(shared)), local(std::make_unique<Local>()) {}

AlignedSampler::AlignedSampler(const AlignedSampler &other)
    : shared(other.shared), local(std::make_unique<Local>()) {}

AlignedSampler::~AlignedSampler() = default;

int AlignedSampler::SamplesPerPixel() const {
    return shared->samplesPerPixel;
}

int AlignedSampler::PrepassSamples() const {
    return shared->prepass;
}

namespace {

void BuildJoint(AlignedSampler::Shared &s, const std::vector<int> &dims, const FileLoc *loc);

// Whether the camera's rays depend on the lens sample: a thin lens with a
// radius (depth of field), or a realistic camera's lens system. Two lens
// samples at a few film points, the same time and wavelengths.
bool LensIsLive(const Camera &camera) {
    const Point2i res = camera.GetFilm().FullResolution();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    for (Point2f f : {Point2f(0.5f, 0.5f), Point2f(0.3f, 0.7f), Point2f(0.8f, 0.2f)}) {
        CameraSample a, b;
        a.pFilm = b.pFilm = Point2f(f.x * res.x, f.y * res.y);
        a.pLens = Point2f(0.2f, 0.3f);
        b.pLens = Point2f(0.7f, 0.9f);
        a.time = b.time = 0.5f;
        pstd::optional<CameraRay> ra = camera.GenerateRay(a, lambda);
        pstd::optional<CameraRay> rb = camera.GenerateRay(b, lambda);
        if (ra.has_value() != rb.has_value())
            return true;
        if (ra && (ra->ray.o != rb->ray.o || ra->ray.d != rb->ray.d))
            return true;
    }
    return false;
}

}  // namespace

void AlignedSampler::StartRender(Bounds2i pixelBounds, const Camera &camera) {
    Shared &s = *shared;
    s.bounds = pixelBounds;
    if (s.Joint()) {
        // No pre-pass values and no plans; with a lens, the lens and time
        // join the lattice (a defocused edge is an edge in the film and lens
        // samples together).
        if (s.jointDefaultDimensions && LensIsLive(camera)) {
            std::vector<int> dims(std::begin(kJointLensFirst), std::end(kJointLensFirst));
            dims.insert(dims.end(), std::begin(kJointDefault), std::end(kJointDefault));
            BuildJoint(s, dims, nullptr);
        }
        return;
    }
    size_t pixels = size_t(pixelBounds.Area());
    s.values.assign(pixels * size_t(s.prepass), 0.0);
    s.planned.assign(pixels, 0);
    s.planner->StartRender(pixels);
}

Float AlignedSampler::RecordSample(Point2i pPixel, int sampleIndex, Float luminance) {
    Shared &s = *shared;
    if (s.Joint())
        return 1;  // every sample weighs the same
    if (s.values.empty())
        LOG_FATAL("AlignedSampler: RecordSample before StartRender");
    if (sampleIndex < s.prepass) {
        CHECK_LT(s.PixelIndex(pPixel), s.planned.size());
        // pbrt has already set a NaN or infinite radiance to black.
        s.values[s.PixelIndex(pPixel) * s.prepass + sampleIndex] =
            std::isfinite(luminance) ? double(luminance) : 0.0;
        return Float(s.prepassWeight / s.prepass);
    }
    return Float((1.0 - s.prepassWeight) / s.main);
}

namespace {

// The pre-pass values of the block around p in the order of a domain's
// pre-pass points: the film's order is the sample order, the light's the
// permuted one (Shared::LightIndex).
void FillBlock(const AlignedSampler::Shared &s, pbrt_alignset::Domain d, Point2i p,
               std::vector<double> &values, std::vector<const double *> &block);

}  // namespace

void AlignedSampler::StartPixelSample(Point2i p, int sampleIndex, int dimension) {
    Shared &s = *shared;
    Local &l = *local;
    l.sampleIndex = sampleIndex;
    l.dimension = dimension;
    const int pass = sampleIndex < s.prepass ? kPassPrepass : kPassMain;
    if (s.Joint()) {
        l.pixel = p;
        l.pass = kPassMain;
        const uint64_t index = uint64_t(p.y) * uint64_t(s.imageWidth) + uint64_t(p.x);
        if (!l.jointView.Valid() || l.jointView.Index() != index)
            l.jointView.Reset(*s.joint, index);
        return;
    }
    if (p == l.pixel && pass == l.pass)
        return;
    l.pixel = p;
    l.pass = pass;
    if (s.values.empty())
        ErrorExit("The \"aligned\" sampler runs only under an integrator that "
                  "renders in pbrt's image tiles (\"path\", \"volpath\", ...).");
    const uint32_t x = uint32_t(p.x), y = uint32_t(p.y);
    // Points only for the aligned dimensions: the others are padded.
    if (pass == kPassPrepass) {
        l.filmPoints.resize(s.prepass);
        l.lightPoints.resize(s.prepass);
        if (s.AlignsFilm())
            s.planner->PrepassPoints(kFilm, x, y, l.filmPoints.data(), *l.scratch);
        if (s.AlignsLight())
            s.planner->PrepassPoints(kLight, x, y, l.lightPoints.data(), *l.scratch);
        return;
    }
    // The pixel's plans, once: its first main sample (the pre-pass wave has
    // finished for every pixel before any main sample starts).
    const size_t index = s.PixelIndex(p);
    if (!s.planned[index]) {
        for (pbrt_alignset::Domain d : {kFilm, kLight}) {
            if (d == kFilm ? !s.AlignsFilm() : !s.AlignsLight())
                continue;  // padded instead
            FillBlock(s, d, p, l.blockValues, l.block);
            if (s.planner->Plan(d, index, x, y, l.block.data(), *l.scratch) > 0)
                ++(d == kFilm ? nFilmDirection : nLightDirection);
        }
        s.planned[index] = 1;
        ++nPlanned;
    }
    l.filmPoints.resize(s.main);
    l.lightPoints.resize(s.main);
    if (s.AlignsFilm())
        s.planner->MainPoints(kFilm, index, l.filmPoints.data(), *l.scratch);
    if (s.AlignsLight())
        s.planner->MainPoints(kLight, index, l.lightPoints.data(), *l.scratch);
    l.third = 0;
    if (s.pairWavelength) {
        if (s.AlignsFilm() && (l.third = s.planner->ThirdMultiplier(kFilm, index)) != 0)
            l.thirdDomain = kFilm;
        else if (s.AlignsLight() && (l.third = s.planner->ThirdMultiplier(kLight, index)) != 0)
            l.thirdDomain = kLight;
        l.thirdShift = double(Hash(p, s.seed, 0x77617665) >> 11) * 0x1p-53;
    }
}

namespace {

Float Padded(const AlignedSampler::Shared &s, Point2i pixel, int pass, int index,
             int count, int dimension, int component) {
    uint64_t hash = Hash(pixel, pass, dimension, s.seed);
    uint32_t i = PermutationElement(uint32_t(index), uint32_t(count), uint32_t(hash));
    return SobolSample(i, component, FastOwenScrambler(uint32_t(hash >> 32) ^ component));
}

}  // namespace

Float AlignedSampler::Get1D() {
    const Shared &s = *shared;
    Local &l = *local;
    const int i = l.IndexInPass(s);
    const int dim = l.dimension++;
    if (s.Joint())
        return s.JointSample(l.jointView, i, dim);
    if (l.pass == kPassMain && dim == kWavelengthDimension && l.third != 0) {
        // The lattice index of this sample's point in the set it pairs with.
        const uint64_t k = l.thirdDomain == kFilm
                               ? uint64_t(i)
                               : uint64_t(s.LightIndex(l.pixel, l.pass, i, s.main));
        double u = double((k * l.third) % uint64_t(s.main)) / s.main + l.thirdShift;
        u -= std::floor(u);
        return std::min(Float(u), OneMinusEpsilon);
    }
    return Padded(s, l.pixel, l.pass, i, l.PassCount(s), dim, 0);
}

Point2f AlignedSampler::Get2D() {
    const Shared &s = *shared;
    Local &l = *local;
    const int i = l.IndexInPass(s), count = l.PassCount(s);
    const int dim = l.dimension;
    l.dimension += 2;
    if (s.Joint())
        return Point2f(s.JointSample(l.jointView, i, dim), s.JointSample(l.jointView, i, dim + 1));
    if (dim == s.lightDimension && s.AlignsLight()) {
        const Point &q = l.lightPoints[s.LightIndex(l.pixel, l.pass, i, count)];
        return Point2f(Float(q.x), Float(q.y));
    }
    return Point2f(Padded(s, l.pixel, l.pass, i, count, dim, 0),
                   Padded(s, l.pixel, l.pass, i, count, dim, 1));
}

Point2f AlignedSampler::GetPixel2D() {
    const Shared &s = *shared;
    Local &l = *local;
    const int i = l.IndexInPass(s), count = l.PassCount(s);
    if (s.Joint())  // the lattice's first two dimensions
        return Point2f(Shared::JointPoint(l.jointView, i, 0), Shared::JointPoint(l.jointView, i, 1));
    if (s.AlignsFilm()) {
        const Point &q = l.filmPoints[i];
        return Point2f(Float(q.x), Float(q.y));
    }
    constexpr int kPixelDimension = -2;  // a dimension of its own, as pbrt's samplers keep
    return Point2f(Padded(s, l.pixel, l.pass, i, count, kPixelDimension, 0),
                   Padded(s, l.pixel, l.pass, i, count, kPixelDimension, 1));
}

namespace {

void FillBlock(const AlignedSampler::Shared &s, pbrt_alignset::Domain d, Point2i p,
               std::vector<double> &values, std::vector<const double *> &block) {
    const int r = s.planner->BlockRadius(d), side = s.planner->BlockSide(d);
    const int m = s.prepass;
    values.resize(size_t(side) * side * m);
    block.assign(size_t(side) * side, nullptr);
    for (int k = 0; k < side * side; ++k) {
        Point2i q(p.x + k % side - r, p.y + k / side - r);
        // Pixel bounds exclude their pMax (pbrt's Inside would include it).
        if (!InsideExclusive(q, s.bounds))
            continue;
        CHECK_LT(s.PixelIndex(q), s.planned.size());
        const double *v = &s.values[s.PixelIndex(q) * m];
        double *out = &values[size_t(k) * m];
        if (d == kFilm)
            std::copy(v, v + m, out);
        else
            for (int i = 0; i < m; ++i)
                out[s.LightIndex(q, kPassPrepass, i, m)] = v[i];
        block[k] = out;
    }
}

}  // namespace

Sampler AlignedSampler::Clone(Allocator alloc) {
    return alloc.new_object<AlignedSampler>(*this);
}

std::string AlignedSampler::ToString() const {
    const Shared &s = *shared;
    if (s.Joint())
        return StringPrintf("[ AlignedSampler align: joint samplesPerPixel: %d seed: %d "
                            "latticeDimensions: %d tented: %d ]",
                            s.samplesPerPixel, s.seed, s.joint->Dimensions(), s.jointTents);
    return StringPrintf("[ AlignedSampler table: %s construction: %s samplesPerPixel: %d "
                        "prepass: %d main: %d seed: %d lightDimension: %d pairWavelength: %s ]",
                        s.tablePath, s.construction, s.samplesPerPixel, s.prepass, s.main,
                        s.seed, s.lightDimension, s.pairWavelength);
}

namespace {

// Builds the lattice over the film and `dims` (sampler dimensions, in
// order): which sampler dimension is which lattice dimension, the folded
// wavelength, the tents ("randomize" "tent": every unfolded one; else those
// of `tented`), the padding's numbering. Called by CreateJoint, and again by
// StartRender where the camera's lens decides the default's dimensions.
void BuildJoint(AlignedSampler::Shared &s, const std::vector<int> &dims, const FileLoc *loc) {
    const int t = s.samplesPerPixel;
    std::fill(std::begin(s.jointOf), std::end(s.jointOf), -1);
    for (size_t k = 0; k < dims.size(); ++k) {
        const int d = dims[k];
        if (d < 0 || d >= kJointMaxDimension)
            ErrorExit(loc, "aligned: \"jointdimensions\" names dimension %d; each must be in "
                           "[0, %d).", d, kJointMaxDimension);
        if (s.jointOf[d] >= 0)
            ErrorExit(loc, "aligned: \"jointdimensions\" names dimension %d twice.", d);
        s.jointOf[d] = int(k) + 2;  // after the film's two
    }
    // The wavelength sample's integrand has period 1 / NSpectrumSamples
    // (SampleVisibleWavelengths draws at u + j / NSpectrumSamples): folded
    // by the library.
    std::vector<uint32_t> folds(dims.size() + 2, 1);
    if (s.jointOf[kWavelengthDimension] >= 0)
        folds[s.jointOf[kWavelengthDimension]] = uint32_t(NSpectrumSamples);
    std::vector<bool> tents(dims.size() + 2, false);
    if (s.jointTentAll)
        for (size_t k = 0; k < tents.size(); ++k)
            tents[k] = folds[k] == 1;
    for (int d : s.jointTented) {
        if (d < 0 || d >= kJointMaxDimension || s.jointOf[d] < 0)
            ErrorExit(loc, "aligned: \"tentdimensions\" names dimension %d, which "
                           "\"jointdimensions\" does not.", d);
        if (folds[s.jointOf[d]] != 1)
            ErrorExit(loc, "aligned: \"tentdimensions\" names dimension %d, the folded "
                           "wavelength (periodic already).", d);
        tents[s.jointOf[d]] = true;
    }
    s.jointTents = int(std::count(tents.begin(), tents.end(), true));
    const int asked = int(dims.size()) + 2;  // the film's two and "jointdimensions"
    for (int d = 0, k = 0; d < kJointMaxDimension; ++d)
        s.jointPadOf[d] = s.jointOf[d] >= 0 ? -1 : asked + k++;
    std::string error;
    s.joint = pbrt_alignset::JointPoints::Create(t, asked, Hash(s.seed, 0x6a6f696e74), folds,
                                                 tents, s.jointJitter, &error);
    if (!s.joint)
        ErrorExit(loc, "aligned: align \"joint\" with %d samples a pixel and %d dimensions: %s",
                  t, asked, error);
}

// align "joint": the lattice over the film and "jointdimensions".
AlignedSampler *CreateJoint(std::shared_ptr<AlignedSampler::Shared> s,
                            const ParameterDictionary &parameters, Point2i fullResolution,
                            const FileLoc *loc, Allocator alloc) {
    const int t = s->samplesPerPixel;
    if (t < 2)
        ErrorExit(loc, "aligned: align \"joint\" needs at least 2 samples a pixel, got %d.", t);
    if (parameters.GetOneInt("prepasssamples", 0) != 0)
        ErrorExit(loc, "aligned: align \"joint\" has no pre-pass; \"prepasssamples\" must be 0 "
                       "or absent.");
    s->prepass = 0;
    s->main = t;
    s->prepassWeight = 0;
    s->imageWidth = std::max(fullResolution.x, 1);
    std::vector<int> dims = parameters.GetIntArray("jointdimensions");
    // Without "jointdimensions" the default's; StartRender puts the lens and
    // time in too where the camera has a lens.
    s->jointDefaultDimensions = dims.empty();
    if (dims.empty())
        dims.assign(std::begin(kJointDefault), std::end(kJointDefault));
    // "randomize": "shift" (a Cranley-Patterson shift a pixel), "jitter"
    // (each point uniform within its stratum, the strata offset a pixel) or
    // "tent" (the shift, then the tent in every lattice dimension but the
    // folded wavelength); "tentdimensions": the shift or the jitter, then
    // the tent in those sampler dimensions of "jointdimensions" only.
    const std::string randomize = parameters.GetOneString("randomize", "shift");
    if (randomize != "shift" && randomize != "jitter" && randomize != "tent")
        ErrorExit(loc, "aligned: \"randomize\" \"%s\" is not \"shift\", \"jitter\" or "
                       "\"tent\".", randomize);
    s->jointTentAll = randomize == "tent";
    s->jointJitter = randomize == "jitter";
    s->jointTented = parameters.GetIntArray("tentdimensions");
    if (!s->jointTented.empty() && randomize == "tent")
        ErrorExit(loc, "aligned: \"tentdimensions\" names the tented dimensions of "
                       "\"randomize\" \"shift\"; \"randomize\" \"tent\" tents them all.");
    BuildJoint(*s, dims, loc);
    return alloc.new_object<AlignedSampler>(std::move(s));
}

}  // namespace

AlignedSampler *AlignedSampler::Create(const ParameterDictionary &parameters,
                                       Point2i fullResolution, const FileLoc *loc,
                                       Allocator alloc) {
    auto s = std::make_shared<Shared>();
    s->samplesPerPixel = parameters.GetOneInt("pixelsamples", 256);
    if (Options->pixelSamples)
        s->samplesPerPixel = *Options->pixelSamples;
    if (Options->quickRender)
        ErrorExit(loc, "aligned: --quick renders one sample a pixel; the aligned "
                       "sampler needs a pre-pass. Use another sampler for a quick look.");
    if (Options->useGPU || Options->wavefront)
        ErrorExit(loc, "aligned: the sampler runs in pbrt's CPU tile renderer only "
                       "(not with --gpu or --wavefront).");
    s->seed = parameters.GetOneInt("seed", Options->seed);
    s->lightDimension = parameters.GetOneInt("lightdimension", 5);
    s->pairWavelength = parameters.GetOneBool("pairwavelength", true);
    s->construction = parameters.GetOneString("construction", "lattice");
    std::string aligned = parameters.GetOneString("align", "film+light");
    if (aligned == "film+light")
        s->aligned = Aligned::kFilmAndLight;
    else if (aligned == "film")
        s->aligned = Aligned::kFilm;
    else if (aligned == "light")
        s->aligned = Aligned::kLight;
    else if (aligned == "none")
        s->aligned = Aligned::kNone;
    else if (aligned == "joint")
        s->aligned = Aligned::kJoint;
    else
        ErrorExit(loc, "aligned: \"align\" is \"%s\"; it must be \"film+light\", \"film\", "
                       "\"light\", \"none\" or \"joint\".", aligned);
    const int t = s->samplesPerPixel;
    if (s->Joint())
        return CreateJoint(std::move(s), parameters, fullResolution, loc, alloc);
    s->prepass = parameters.GetOneInt("prepasssamples", t / 4);
    s->main = t - s->prepass;
    if (s->prepass < 16 || s->main < 1)
        ErrorExit(loc, "aligned: %d samples a pixel with a pre-pass of %d leave no room "
                       "for both: the pre-pass needs at least 16 samples and the main "
                       "samples at least one (at the default pre-pass of a quarter, at "
                       "least 64 samples a pixel).", t, s->prepass);

    s->tablePath = parameters.GetOneString("table", "");
    if (s->tablePath.empty())
        ErrorExit(loc, "aligned: no \"string table\": the sampler reads its sets from a "
                       "table file that `alignset export` writes (docs/sampler.md).");
    s->tablePath = ResolveFilename(s->tablePath);
    Planner::Config config;
    config.table = s->tablePath;
    config.construction = s->construction;
    config.prepass = s->prepass;
    config.main = s->main;
    config.imageWidth = std::max(fullResolution.x, 1);
    config.stackRadius = parameters.GetOneInt("stackradius", 0);
    // pbrt's wavelengths of a sample lie at u + j / NSpectrumSamples.
    config.thirdHarmonic = NSpectrumSamples;
    if (config.stackRadius < 0 || config.stackRadius > 4)
        ErrorExit(loc, "aligned: \"stackradius\" is %d; it must be 0 (the library's choice) to 4.",
                  config.stackRadius);
    config.seed[kFilm] = Hash(s->seed, 0x66696c6d);
    config.seed[kLight] = Hash(s->seed, 0x6c696768);
    std::string error;
    s->planner = Planner::Create(config, &error);
    if (!s->planner)
        ErrorExit(loc, "aligned: the table \"%s\" for %d samples a pixel (a pre-pass of %d "
                       "and %d main samples): %s",
                  s->tablePath, t, s->prepass, s->main, error);
    s->prepassWeight = s->planner->PrepassWeight();
    return alloc.new_object<AlignedSampler>(std::move(s));
}

}  // namespace pbrt
