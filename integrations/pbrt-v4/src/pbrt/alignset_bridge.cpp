// alignset's sampler library behind the C++17 interface of alignset_bridge.h
// (compiled as C++20; no pbrt header here).

#include "alignset_bridge.h"

#include <alignset/aligned_sampler.h>
#include <alignset/joint_lattice.h>
#include <alignset/set_table.h>

#include <cmath>
#include <cstdlib>
#include <numeric>
#include <span>
#include <vector>

namespace pbrt_alignset {

struct Planner::Scratch {
    alignset::AlignedSampler::Scratch library[2];
    std::vector<alignset::Point2> points;
    std::vector<std::span<const double>> block;
};

struct Planner::Impl {
    Config config;
    std::shared_ptr<const alignset::SetTable> table;
    alignset::AlignedSampler sampler[2];
    std::vector<alignset::PixelPlan> plans[2];
    std::vector<uint32_t> third[2];  // ThirdMultiplier per pixel
};

Planner::Planner(std::unique_ptr<Impl> impl) : impl(std::move(impl)) {}
Planner::~Planner() = default;

std::unique_ptr<Planner> Planner::Create(const Config &config, std::string *error) {
    auto impl = std::make_unique<Impl>();
    impl->config = config;
    auto table = alignset::SetTable::Load(config.table);
    if (!table.ok()) {
        *error = table.status().ToString();
        return nullptr;
    }
    impl->table = *table;
    alignset::AlignedSamplerOptions options;
    options.n = uint32_t(config.main);
    options.construction = config.construction;
    options.image_width = uint32_t(config.imageWidth);
    options.prepass_samples = uint32_t(config.prepass);
    for (int d : {kFilm, kLight}) {
        options.domain = d == kFilm ? alignset::PixelDomain::kFootprint : alignset::PixelDomain::kShared;
        options.seed = config.seed[d];
        options.stack_radius = d == kLight ? config.stackRadius : 0;
        auto sampler = alignset::AlignedSampler::Create(impl->table, options);
        if (!sampler.ok()) {
            *error = sampler.status().ToString();
            return nullptr;
        }
        impl->sampler[d] = std::move(*sampler);
    }
    return std::unique_ptr<Planner>(new Planner(std::move(impl)));
}

double Planner::PrepassWeight() const {
    return impl->sampler[kFilm].PrepassWeight();
}

int Planner::BlockRadius(Domain d) const {
    return impl->sampler[d].block_radius();
}

int Planner::BlockSide(Domain d) const {
    return impl->sampler[d].block_side();
}

std::unique_ptr<Planner::Scratch, void (*)(Planner::Scratch *)> Planner::NewScratch() {
    return {new Scratch(), [](Scratch *s) { delete s; }};
}

void Planner::StartRender(size_t pixels) {
    for (int d : {kFilm, kLight}) {
        impl->plans[d].assign(pixels, alignset::PixelPlan());
        impl->third[d].assign(pixels, 0);
    }
}

namespace {

// The multiplier h of ThirdMultiplier for the lattice (1, g) / N aligned to
// the edge normals `normals_deg` (one or two). The shifted 3-D lattice's
// error is the integrand's Fourier coefficients summed over its dual
// vectors k = (k1, k2, k3), k1 + g k2 + h k3 = 0 (mod N). For a pixel whose
// integrand is a step in the 2-D sample times a smooth function of the third
// (f(x) c(w)), the terms with k3 != 0 weigh |c^(k3)|^2 times |f^(k1, k2)|^2.
// c has period 1 / `harmonic` (pbrt draws its four wavelengths at w, w + 1/4,
// w + 1/2, w + 3/4: only every fourth frequency is live), so the k3 that
// count are harmonic, 2 harmonic, 3 harmonic, weighed 1, 1/16, 1/81 (a
// smooth c's coefficients fall fast); |f^|^2 which is large near the
// step's normal line and the axes (the pixel's own boundary) and falls as
// 1/|k|^2. So: accumulate that weight of every small (k1, k2) into the
// residue k1 + g k2 (mod N) it lies in, and take the h (coprime to N, so
// the third coordinate alone is stratified) whose residues -h k3 carry the
// least.
uint32_t ChooseThird(uint32_t n, uint32_t g, const double *normals_deg, int count, int harmonic) {
    if (n < 8)
        return 0;
    std::vector<double> weight(n, 0.0);
    const int radius = int(std::min<double>(48.0, 2.0 * std::sqrt(double(n)) + 4.0));
    double nx[2], ny[2];
    for (int j = 0; j < count; ++j) {
        const double a = normals_deg[j] * M_PI / 180.0;
        nx[j] = std::cos(a);
        ny[j] = std::sin(a);
    }
    for (int k1 = -radius; k1 <= radius; ++k1) {
        for (int k2 = -radius; k2 <= radius; ++k2) {
            if (k1 == 0 && k2 == 0)
                continue;
            const double r2 = double(k1) * k1 + double(k2) * k2;
            // Distance of k from each normal line and from the axes.
            double near = 0.5 * (std::exp(-double(k1) * k1) + std::exp(-double(k2) * k2));
            for (int j = 0; j < count; ++j) {
                const double off = -double(k1) * ny[j] + double(k2) * nx[j];
                near += std::exp(-off * off);
            }
            const int64_t residue = ((int64_t(k1) + int64_t(g) * k2) % int64_t(n) + n) % n;
            weight[size_t(residue)] += near / r2;
        }
    }
    uint32_t best = 0;
    double bestCost = 0;
    for (uint32_t h = 1; h < n; ++h) {
        if (std::gcd(h, n) != 1)
            continue;
        double cost = 0;
        for (int j = 1; j <= 3; ++j) {
            const double w = 1.0 / (double(j) * j * j * j);
            const uint64_t r = (uint64_t(h) * uint64_t(j * harmonic)) % n;
            cost += w * (weight[r] + weight[(n - r) % n]);
        }
        if (best == 0 || cost < bestCost) {
            best = h;
            bestCost = cost;
        }
    }
    return best;
}

}  // namespace

void Planner::PrepassPoints(Domain d, uint32_t x, uint32_t y, Point *out, Scratch &scratch) const {
    const size_t m = size_t(impl->config.prepass);
    scratch.points.resize(m);
    impl->sampler[d].PrepassPoints(x, y, scratch.points);
    for (size_t i = 0; i < m; ++i)
        out[i] = {scratch.points[i].x, scratch.points[i].y};
}

int Planner::Plan(Domain d, size_t pixel, uint32_t x, uint32_t y, const double *const *block,
                   Scratch &scratch) {
    const alignset::AlignedSampler &s = impl->sampler[d];
    const int side = s.block_side();
    const size_t m = size_t(impl->config.prepass);
    scratch.block.assign(size_t(side) * side, std::span<const double>());
    for (int k = 0; k < side * side; ++k)
        if (block[k])
            scratch.block[k] = std::span<const double>(block[k], m);
    auto plan = s.Plan(x, y, scratch.block, scratch.library[d]);
    // The block's shape is this file's to get right: a refusal is a bug here.
    if (!plan.ok())
        std::abort();
    impl->plans[d][pixel] = *plan;
    if (plan->main == alignset::PixelPlan::Main::kSet && plan->set.lattice_generator != 0 &&
        !plan->set.folded) {
        const double normals[2] = {plan->theta1_deg, plan->theta2_deg};
        const int count = plan->choice.kind == alignset::SetChoice::Kind::kTwo ? 2 : 1;
        impl->third[d][pixel] =
            ChooseThird(plan->set.n, plan->set.lattice_generator, normals, count, impl->config.thirdHarmonic);
    }
    return plan->directions;
}

void Planner::MainPoints(Domain d, size_t pixel, Point *out, Scratch &scratch) const {
    const size_t n = size_t(impl->config.main);
    scratch.points.resize(n);
    impl->sampler[d].MainPoints(impl->plans[d][pixel], scratch.points);
    for (size_t i = 0; i < n; ++i)
        out[i] = {scratch.points[i].x, scratch.points[i].y};
}

uint32_t Planner::ThirdMultiplier(Domain d, size_t pixel) const {
    return impl->third[d][pixel];
}

struct JointPoints::Impl {
    alignset::JointLattice lattice;
};

JointPoints::JointPoints(std::unique_ptr<Impl> impl) : impl(std::move(impl)) {}
JointPoints::~JointPoints() = default;

std::unique_ptr<JointPoints> JointPoints::Create(int n, int dimensions, uint64_t seed,
                                                 const std::vector<uint32_t> &folds,
                                                 const std::vector<bool> &tents, bool jitter,
                                                 std::string *error) {
    if (n < 0 || dimensions < 0) {
        *error = "joint lattice: N and the dimension count must not be negative";
        return nullptr;
    }
    auto lattice =
        alignset::JointLattice::Create(uint32_t(n), uint32_t(dimensions), seed, folds, tents,
                                       jitter);
    if (!lattice.ok()) {
        *error = lattice.status().ToString();
        return nullptr;
    }
    auto impl = std::make_unique<Impl>();
    impl->lattice = std::move(*lattice);
    return std::unique_ptr<JointPoints>(new JointPoints(std::move(impl)));
}

int JointPoints::Dimensions() const {
    return int(impl->lattice.dimensions());
}

double JointPoints::Sample(uint64_t pixel, uint32_t i, uint32_t d) const {
    return impl->lattice.Sample(pixel, i, d);
}

struct JointPoints::Pixel::Impl {
    alignset::JointLatticePixel view;
};

JointPoints::Pixel::Pixel() : impl(std::make_unique<Impl>()) {}
JointPoints::Pixel::~Pixel() = default;

void JointPoints::Pixel::Reset(const JointPoints &points, uint64_t pixel) {
    impl->view.Reset(points.impl->lattice, pixel);
}

bool JointPoints::Pixel::Valid() const {
    return impl->view.valid();
}

uint64_t JointPoints::Pixel::Index() const {
    return impl->view.pixel();
}

double JointPoints::Pixel::Sample(uint32_t i, uint32_t d) {
    return impl->view.Sample(i, d);
}

}  // namespace pbrt_alignset
