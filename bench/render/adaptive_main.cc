// Adaptive sampling with each sampler: every pixel of a scene stops once its
// own error estimate, |I_k - I_(k/2)| between the estimate after k main
// samples and after k/2, falls below a threshold tau (with --consecutive 2:
// at two stages in a row, a stricter rule that an unlucky agreement of two
// estimates does not satisfy; or at 4096 samples);
// swept over tau, each sampler traces samples spent against the edge pixels'
// error. Samplers:
//   lattice-sequence  the sampler library (<alignset/aligned_sampler.h>) on a
//                     table of aligned lattice sequences: the pre-pass, the
//                     plan, then the first k points of the pixel's sequence;
//   lattice           the same pre-pass and plan, but the fixed-size aligned
//                     lattice of k points at each stage (a new set per
//                     stage: every stage's samples are spent);
//   owen-sobol        the pixel's own Owen-scrambled Sobol sequence, k points;
//   pmj02bn           a pool of 16 pmj02bn sequences of 4096 points, one per
//                     pixel under the pixel's Cranley-Patterson shift;
//   lattice-sequence-no-prepass  the first sampler with the pre-pass's
//                     values left out of the estimate (spent on the plan only).
// A pixel with no direction reads the library's fallback, the pixel's own
// Owen-Sobol sequence, in both aligned samplers. Every sample counts (the
// pre-pass and every stage), and the estimates are the library's (the
// pre-pass weighted beside the k main samples).
//
//   build/bench/render/adaptive_render --scene antialias --seeds 71,72,73 --out bench/results/adaptive
//   (--size 64, --prepass 32, --consecutive 1; the tables are built once into --tables)
#include <alignset/aligned_sampler.h>
#include <alignset/set_table.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/lattice_sequence.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/pmj02.h"
#include "core/util/hash.h"
#include "render/parallel.h"
#include "render/scene.h"

namespace alignset {
namespace {

constexpr uint32_t kMaxMain = 4096;
constexpr uint32_t kFirstStage = 32;

std::vector<std::vector<double>> OneDirectionKeys() {
  std::vector<std::vector<double>> out;
  for (size_t i = 0; i < CanonicalKeyCount(1, AngleGrid::kWholeDegree); ++i) {
    out.push_back({Phi1Degrees(CanonicalKeyAt(1, i, AngleGrid::kWholeDegree))});
  }
  return out;
}

// The sequences of the 46 one-direction keys (realization 0, what a cache
// holds and `alignset export` writes) and the fixed-size lattices of every
// stage's N.
StatusOr<std::shared_ptr<const SetTable>> Tables(const std::string& path) {
  if (std::filesystem::exists(path)) return SetTable::Load(path);
  const auto keys = OneDirectionKeys();
  std::vector<TableSection> sections;
  TableSection seq;
  seq.n = kMaxMain;
  seq.construction = "lattice-sequence";
  seq.space = TableSpace::kOneDirection;
  for (size_t k = 0; k < keys.size(); ++k) {
    LatticeSequenceOptions o;
    o.threads = 0;
    auto c = ChooseLatticeSequenceGenerator(keys[k], o);
    if (!c.ok()) return c.status();
    seq.sets.push_back(LatticeSequencePoints(kMaxMain, c->generator, 0));
    std::fprintf(stderr, "\rsequence keys %zu/%zu", k + 1, keys.size());
  }
  std::fprintf(stderr, "\n");
  sections.push_back(std::move(seq));
  for (uint32_t n = kFirstStage; n <= kMaxMain; n *= 2) {
    AlignedLatticeOptions o;
    o.threads = 0;
    auto choices = ChooseAlignedLatticeGenerators(n, keys, o);
    if (!choices.ok()) return choices.status();
    TableSection s;
    s.n = n;
    s.construction = "lattice";
    s.space = TableSpace::kOneDirection;
    for (const AlignedLatticeChoice& c : *choices) s.generators.push_back(c.generator);
    sections.push_back(std::move(s));
  }
  auto table = SetTable::FromSections(std::move(sections));
  if (!table.ok()) return table.status();
  if (Status s = (*table)->Save(path); !s.ok()) return s;
  return table;
}

struct Curve {  // per stage: the estimate, the error estimate, the samples spent so far
  std::vector<double> estimate, error, spent;
};

void FillCurve(const std::vector<double>& estimates, const std::vector<double>& spent, Curve* c) {
  c->estimate = estimates;
  c->spent = spent;
  c->error.assign(estimates.size(), INFINITY);
  for (size_t s = 1; s < estimates.size(); ++s) c->error[s] = std::fabs(estimates[s] - estimates[s - 1]);
}

double Mean(const double* v, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += v[i];
  return s / static_cast<double>(n);
}

int Run(int argc, char** argv) {
  std::string scene_name = "antialias", out_dir = "bench/results/adaptive", tables = "build/adaptive-tables.tbl";
  std::vector<uint64_t> seeds = {71, 72, 73};
  int size = 64;
  uint32_t prepass = 32;
  int consecutive = 1;  // stages in a row whose error estimate must be below tau
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--scene") scene_name = v;
    else if (a == "--out") out_dir = v;
    else if (a == "--tables") tables = v;
    else if (a == "--size") size = std::atoi(v.c_str());
    else if (a == "--prepass") prepass = static_cast<uint32_t>(std::atoi(v.c_str()));
    else if (a == "--consecutive") consecutive = std::max(1, std::atoi(v.c_str()));
    else if (a == "--seeds") {
      seeds.clear();
      for (const char* p = v.c_str(); *p;) {
        seeds.push_back(std::strtoull(p, const_cast<char**>(&p), 10));
        if (*p == ',') ++p;
      }
    } else {
      std::fprintf(stderr, "adaptive_render: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  auto table = Tables(tables);
  if (!table.ok()) {
    std::fprintf(stderr, "adaptive_render: %s\n", table.status().ToString().c_str());
    return 1;
  }
  std::vector<PointSet> pmj_pool;
  for (uint64_t j = 0; j < 16; ++j) pmj_pool.push_back(*Pmj02(kMaxMain, 9000 + j, kPmj02bnCandidates));
  std::filesystem::create_directories(out_dir);
  const std::string tsv_path =
      out_dir + "/" + scene_name + (consecutive > 1 ? "_consecutive" + std::to_string(consecutive) : "") + ".tsv";
  FILE* tsv = std::fopen(tsv_path.c_str(), "w");
  std::fprintf(tsv, "scene\tseed\tsampler\ttau\tedge_samples\tedge_mse\tall_samples\tall_mse\n");
  std::vector<double> taus;
  for (double t = 3e-2; t > 2e-6; t /= std::sqrt(2.0)) taus.push_back(t);
  const char* names[] = {"lattice-sequence", "lattice", "owen-sobol", "pmj02bn", "lattice-sequence-no-prepass"};
  for (uint64_t seed : seeds) {
    auto scene = render::MakeScene(scene_name, size, size, seed);
    if (!scene.ok()) {
      std::fprintf(stderr, "adaptive_render: %s\n", scene.status().ToString().c_str());
      return 2;
    }
    const std::vector<double> reference = scene->Reference();
    const std::vector<render::PixelClass> classes = scene->Classes();
    AlignedSamplerOptions so;
    so.n = kMaxMain;
    so.construction = "lattice-sequence";
    so.domain = scene->domain() == render::PixelDomain::kShared ? PixelDomain::kShared : PixelDomain::kFootprint;
    so.image_width = static_cast<uint32_t>(size);
    so.seed = seed * 7919 + 1;
    so.prepass_samples = prepass;
    so.prepass_points = AlignedSamplerOptions::PrepassPoints::kLattice;
    so.stack_radius = 2;
    so.two_directions = false;
    auto sampler = AlignedSampler::Create(*table, so);
    if (!sampler.ok()) {
      std::fprintf(stderr, "adaptive_render: %s\n", sampler.status().ToString().c_str());
      return 1;
    }
    const size_t pixels = scene->size();
    const int m = static_cast<int>(sampler->prepass_samples());
    std::vector<std::vector<double>> pre(pixels, std::vector<double>(m));
    render::ParallelFor(pixels, threads, [&](size_t i) {
      const int x = static_cast<int>(i) % size, y = static_cast<int>(i) / size;
      std::vector<Point2> pts(m);
      sampler->PrepassPoints(x, y, pts);
      for (int j = 0; j < m; ++j) pre[i][j] = scene->Pixel(i).Eval({pts[j].x, pts[j].y});
    });
    std::vector<std::vector<Curve>> curves(5, std::vector<Curve>(pixels));
    const int r = sampler->block_radius();
    render::ParallelFor(pixels, threads, [&](size_t i) {
      thread_local AlignedSampler::Scratch scratch;
      const int x = static_cast<int>(i) % size, y = static_cast<int>(i) / size;
      const render::PixelIntegrand& f = scene->Pixel(i);
      std::vector<std::span<const double>> block;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx, yy = y + dy;
          block.push_back(xx < 0 || yy < 0 || xx >= size || yy >= size ? std::span<const double>()
                                                                        : std::span<const double>(pre[yy * size + xx]));
        }
      }
      auto plan = sampler->Plan(x, y, block, scratch);
      if (!plan.ok()) std::abort();
      std::vector<Point2> pts(kMaxMain);
      std::vector<double> values(kMaxMain);
      std::vector<double> est, spent;
      // The sequence (or the fallback's Owen-Sobol sequence): prefixes.
      sampler->MainPoints(*plan, pts);
      for (uint32_t j = 0; j < kMaxMain; ++j) values[j] = f.Eval({pts[j].x, pts[j].y});
      for (uint32_t k = kFirstStage; k <= kMaxMain; k *= 2) {
        est.push_back(sampler->Estimate(*plan, pre[i], std::span<const double>(values.data(), k)));
        spent.push_back(m + k);
      }
      FillCurve(est, spent, &curves[0][i]);
      // The pre-pass question: the same sequence with the pre-pass spent on
      // the plan alone, its values left out of the estimate.
      if (plan->main == PixelPlan::Main::kSet) {
        est.clear();
        double sum = 0.0;
        uint32_t done = 0;
        for (uint32_t k = kFirstStage; k <= kMaxMain; k *= 2) {
          for (; done < k; ++done) sum += values[done];
          est.push_back(sum / k);
        }
      }
      FillCurve(est, spent, &curves[4][i]);
      // Fixed-size lattices, a new one each stage.
      est.clear(), spent.clear();
      double total = m;
      for (uint32_t k = kFirstStage; k <= kMaxMain; k *= 2) {
        std::span<Point2> stage(pts.data(), k);
        if (plan->main == PixelPlan::Main::kSet) {
          auto set = (*table)->Find(k, "lattice", plan->choice);
          if (!set.ok()) std::abort();
          SetPixelPoints(*set, plan->shift, stage);
          double mean = 0.0;
          for (uint32_t j = 0; j < k; ++j) mean += f.Eval({stage[j].x, stage[j].y});
          mean /= k;
          const double w = PrepassWeight(static_cast<uint32_t>(m), k);
          est.push_back(w * Mean(pre[i].data(), m) + (1 - w) * mean);
          total += k;
        } else {  // the fallback is progressive: as the sequence's
          est.push_back(curves[0][i].estimate[est.size()]);
          total = curves[0][i].spent[spent.size()];
        }
        spent.push_back(total);
      }
      FillCurve(est, spent, &curves[1][i]);
      // Owen-Sobol and pmj02bn: no pre-pass, the pixel's own prefixes.
      for (int s = 2; s < 4; ++s) {
        est.clear(), spent.clear();
        if (s == 2) {
          OwenScrambledSobolInto(HashCombine(so.seed, 0x6f77656e00000000ull + static_cast<uint64_t>(i)), 0, pts);
        } else {
          const PointSet& p = pmj_pool[HashCombine(so.seed, static_cast<uint64_t>(i)) % pmj_pool.size()];
          Pcg32 rng(HashCombine(so.seed ^ 0x706d6a, static_cast<uint64_t>(i)));
          const double sx = rng.NextDouble(), sy = rng.NextDouble();
          for (uint32_t j = 0; j < kMaxMain; ++j) {
            pts[j] = {std::fmod(p[j].x + sx, 1.0), std::fmod(p[j].y + sy, 1.0)};
          }
        }
        double sum = 0.0;
        uint32_t done = 0;
        for (uint32_t k = kFirstStage; k <= kMaxMain; k *= 2) {
          for (; done < k; ++done) sum += f.Eval({pts[done].x, pts[done].y});
          est.push_back(sum / k);
          spent.push_back(k);
        }
        FillCurve(est, spent, &curves[s][i]);
      }
    });
    for (int s = 0; s < 5; ++s) {
      for (double tau : taus) {
        double edge_n = 0, edge_e = 0, all_n = 0, all_e = 0;
        size_t edges = 0;
        for (size_t i = 0; i < pixels; ++i) {
          const Curve& c = curves[s][i];
          size_t stop = c.estimate.size() - 1;
          for (size_t st = static_cast<size_t>(consecutive); st < c.estimate.size(); ++st) {
            bool below = true;
            for (int back = 0; back < consecutive; ++back) below = below && c.error[st - back] < tau;
            if (below) {
              stop = st;
              break;
            }
          }
          const double e = (c.estimate[stop] - reference[i]) * (c.estimate[stop] - reference[i]);
          all_n += c.spent[stop];
          all_e += e;
          if (classes[i] == render::PixelClass::kEdge) {
            edge_n += c.spent[stop];
            edge_e += e;
            ++edges;
          }
        }
        std::fprintf(tsv, "%s\t%llu\t%s\t%.4g\t%.2f\t%.4e\t%.2f\t%.4e\n", scene_name.c_str(),
                     static_cast<unsigned long long>(seed), names[s], tau, edge_n / edges, edge_e / edges,
                     all_n / pixels, all_e / pixels);
      }
    }
    std::fflush(tsv);
    std::fprintf(stderr, "%s seed %llu done\n", scene_name.c_str(), static_cast<unsigned long long>(seed));
  }
  std::fclose(tsv);
  std::printf("wrote %s\n", tsv_path.c_str());
  return 0;
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) { return alignset::Run(argc, argv); }
