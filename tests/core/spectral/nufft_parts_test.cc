// The building blocks of the fast engine: kernel, lattice bases, partition.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "core/spectral/frequency_partition.h"
#include "core/spectral/frequency_set.h"
#include "core/spectral/lattice_basis.h"
#include "core/spectral/nufft_grid.h"
#include "core/spectral/nufft_kernel.h"
#include "core/spectral/nufft_loops.h"

namespace alignset {
namespace {

TEST(EsKernelTest, PolynomialWeightsMatchTheKernel) {
  for (double tol : {1e-3, 1e-6, 1e-9, 1e-12}) {
    const EsKernel kernel(tol);
    double fast[EsKernel::kMaxWidth], exact[EsKernel::kMaxWidth];
    double max_error = 0.0, sum = 0.0;
    for (int i = 0; i <= 1000; ++i) {
      const double x = 37.0 + i / 1000.0;
      const int first = kernel.Weights(x, fast);
      ASSERT_EQ(first, kernel.ExactWeights(x, exact));
      ASSERT_LE(std::abs(x - first), 0.5 * kernel.width());
      for (int t = 0; t < kernel.width(); ++t) {
        max_error = std::max(max_error, std::abs(fast[t] - exact[t]));
        EXPECT_NEAR(exact[t], kernel.Value(x - first - t), 1e-15);
      }
      if (i == 500) {
        for (int t = 0; t < kernel.width(); ++t) sum += exact[t];
      }
    }
    EXPECT_LT(max_error, 0.1 * tol) << "tolerance " << tol;
    EXPECT_GT(sum, 1.0);  // the taps cover the kernel's peak
  }
}

TEST(EsKernelTest, FourierTransformMatchesARiemannSum) {
  const EsKernel kernel(1e-9);
  const int n = 64;
  const std::vector<double> ft = kernel.FourierTransform(n, 20);
  for (int k : {0, 5, 20}) {
    // phi is smooth and (up to e^-beta) zero at the ends: a fine midpoint
    // rule converges fast.
    const int steps = 20000;
    const double h = kernel.width() / static_cast<double>(steps);
    double s = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double z = -0.5 * kernel.width() + (i + 0.5) * h;
      s += kernel.Value(z) * std::cos(2.0 * 3.141592653589793 * k * z / n) * h;
    }
    EXPECT_NEAR(ft[k], s, 1e-7 * ft[0]) << k;
  }
  EXPECT_GT(ft[0], ft[20]);
}

TEST(FastFftSizeTest, SmallestSevenSmoothSize) {
  EXPECT_EQ(FastFftSize(1), 1);
  EXPECT_EQ(FastFftSize(11), 12);
  EXPECT_EQ(FastFftSize(258), 270);
  EXPECT_EQ(FastFftSize(4098), 4116);
  EXPECT_EQ(FastFftSize(4096), 4096);
}

TEST(LatticeBasisTest, ObliqueStripBecomesThin) {
  // A 30-degree strip of N = 65536 (length 1024, width 17).
  FrequencyParams p = DefaultFrequencyParams(65536);
  const std::vector<Frequency> strip = StripFrequencies(p, 30.0);
  std::vector<Frequency> sym;
  for (const Frequency& v : strip) {
    sym.push_back(v);
    sym.push_back({-v.a, -v.b});
  }
  const std::vector<Frequency> hull = ConvexHull(sym);
  auto cells = [](int64_t m1, int64_t m2) {
    return static_cast<double>(2 * m1 + 1) * static_cast<double>(2 * m2 + 1);
  };
  const BasisBox identity = BoxInBasis(hull, LatticeBasis{});
  const double angle = 30.0 * 3.141592653589793 / 180.0;
  const BasisBox best = BestBasis(hull, angle, angle, 0.05, 40, cells);
  EXPECT_EQ(std::abs(best.basis.det()), 1);
  // Every strip frequency is inside the box, and the box is a small
  // multiple of the strip's own area, far below the bounding box's.
  for (const Frequency& v : sym) {
    ASSERT_LE(std::abs(best.basis.W1(v.a, v.b)), best.m1);
    ASSERT_LE(std::abs(best.basis.W2(v.a, v.b)), best.m2);
    // And the coordinates really are coordinates: v = w1 p + w2 q.
    const int64_t w1 = best.basis.W1(v.a, v.b), w2 = best.basis.W2(v.a, v.b);
    ASSERT_EQ(w1 * best.basis.p1 + w2 * best.basis.q1, v.a);
    ASSERT_EQ(w1 * best.basis.p2 + w2 * best.basis.q2, v.b);
  }
  EXPECT_LT(cells(best.m1, best.m2), 2.5 * static_cast<double>(sym.size()));
  EXPECT_LT(cells(best.m1, best.m2), 0.1 * cells(identity.m1, identity.m2));
}

// BestBasis reads its candidates from a table and finds the shear by
// bisection; the reference tries every primitive p in the window in the
// same order and every shear, so ties must fall the same way too.
TEST(LatticeBasisTest, BestBasisEqualsAnExhaustiveSearch) {
  std::mt19937 rng(7);
  auto cost = [](int64_t m1, int64_t m2) {
    const double c = static_cast<double>(2 * m1 + 1) * static_cast<double>(2 * m2 + 1);
    return 500.0 + c * std::log2(c);
  };
  auto reference = [&](const std::vector<Frequency>& hull, double lo, double hi, double margin,
                       int max_component) {
    BasisBox best = BoxInBasis(hull, LatticeBasis{});
    double best_cost = cost(best.m1, best.m2);
    const double pi = 3.141592653589793;
    auto in_window = [&](double a) {
      if (hi - lo + 2 * margin >= pi) return true;
      while (a < lo - margin) a += pi;
      while (a - pi >= lo - margin) a -= pi;
      return a <= hi + margin;
    };
    for (int64_t p2 = 0; p2 <= max_component; ++p2) {
      for (int64_t p1 = -max_component; p1 <= max_component; ++p1) {
        if (!(p2 > 0 || p1 > 0) || std::gcd(p1, p2) != 1) continue;
        if (!in_window(std::atan2(static_cast<double>(p2), static_cast<double>(p1)))) continue;
        // Some q completing p, by search (|q| small suffices for the test).
        LatticeBasis b;
        bool found = false;
        for (int64_t q1 = -max_component; q1 <= max_component && !found; ++q1) {
          for (int64_t q2 = -max_component; q2 <= max_component && !found; ++q2) {
            if (p1 * q2 - p2 * q1 == 1) {
              b = {p1, p2, q1, q2};
              found = true;
            }
          }
        }
        if (!found) {
          ADD_FAILURE() << "no q completes (" << p1 << ", " << p2 << ")";
          continue;
        }
        // Every shear q + k p that could matter; the first minimum.
        const int64_t reach = 4 * (BoxInBasis(hull, b).m1 + std::abs(b.q1) + std::abs(b.q2)) + 4;
        BasisBox local = BoxInBasis(hull, {p1, p2, b.q1 - reach * p1, b.q2 - reach * p2});
        for (int64_t k = -reach + 1; k <= reach; ++k) {
          const BasisBox box = BoxInBasis(hull, {p1, p2, b.q1 + k * p1, b.q2 + k * p2});
          if (box.m1 < local.m1) local = box;
        }
        if (cost(local.m1, local.m2) < best_cost) {
          best_cost = cost(local.m1, local.m2);
          best = local;
        }
      }
    }
    return std::make_pair(best, best_cost);
  };
  std::uniform_int_distribution<int> c(-90, 90);
  std::uniform_real_distribution<double> angle(0.0, 3.141592653589793);
  for (int trial = 0; trial < 40; ++trial) {
    // A thin random strip: points near a line at a random angle.
    const double t = angle(rng);
    std::vector<Frequency> pts;
    for (int i = 0; i < 60; ++i) {
      const double along = c(rng), across = 0.05 * c(rng);
      pts.push_back({static_cast<int32_t>(std::lround(along * std::cos(t) - across * std::sin(t))),
                     static_cast<int32_t>(std::lround(along * std::sin(t) + across * std::cos(t)))});
      pts.push_back({-pts.back().a, -pts.back().b});
    }
    const std::vector<Frequency> hull = ConvexHull(pts);
    const int max_component = trial % 4 == 3 ? 70 : 40;  // beyond the table too
    const double lo = t - 0.02, hi = t + 0.01 * (trial % 3);
    const BasisBox fast = BestBasis(hull, lo, hi, 0.05, max_component, cost);
    const auto [slow, slow_cost] = reference(hull, lo, hi, 0.05, max_component);
    ASSERT_EQ(cost(fast.m1, fast.m2), slow_cost) << "trial " << trial;
    EXPECT_EQ(fast.basis.p1, slow.basis.p1) << "trial " << trial;
    EXPECT_EQ(fast.basis.p2, slow.basis.p2) << "trial " << trial;
    EXPECT_EQ(fast.basis.q1, slow.basis.q1) << "trial " << trial;
    EXPECT_EQ(fast.basis.q2, slow.basis.q2) << "trial " << trial;
    EXPECT_EQ(fast.m1, slow.m1);
    EXPECT_EQ(fast.m2, slow.m2);
  }
}

TEST(FrequencyPartitionTest, CoversEveryEntryOnceInsideItsBox) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> c(-60, 60);
  std::vector<std::vector<Frequency>> sets = {
      BuildFrequencySet(DefaultFrequencyParams(4096), AnisotropyDirections({30.0})),
      BuildFrequencySet(DefaultFrequencyParams(700), AnisotropyDirections({100.0, 12.0})),
      BuildFrequencySet(DefaultFrequencyParams(16), AnisotropyDirections({45.0}))};
  std::vector<Frequency> random;
  for (int i = 0; i < 300; ++i) random.push_back({c(rng), c(rng)});
  sets.push_back(random);
  auto cost = [](int64_t m1, int64_t m2) {
    return 1000.0 + static_cast<double>(2 * m1 + 1) * static_cast<double>(2 * m2 + 1);
  };
  for (const std::vector<Frequency>& k : sets) {
    const std::vector<FrequencyPiece> pieces = PartitionFrequencies(k, cost);
    std::vector<int> seen(k.size(), 0);
    for (const FrequencyPiece& piece : pieces) {
      EXPECT_EQ(std::abs(piece.box.basis.det()), 1);
      for (uint32_t i : piece.members) {
        ASSERT_LT(i, k.size());
        ++seen[i];
        EXPECT_LE(std::abs(piece.box.basis.W1(k[i].a, k[i].b)), piece.box.m1);
        EXPECT_LE(std::abs(piece.box.basis.W2(k[i].a, k[i].b)), piece.box.m2);
      }
    }
    for (int s : seen) ASSERT_EQ(s, 1);
  }
}

TEST(FrequencyPartitionTest, FindsTheDiskAndOnePiecePerStrip) {
  const FrequencyParams p = DefaultFrequencyParams(16384);
  const std::vector<Frequency> k = BuildFrequencySet(p, AnisotropyDirections({30.0}));
  EXPECT_EQ(ContainedDiskRadius(k), static_cast<int>(std::floor(p.radius)));
  auto cost = [](int64_t m1, int64_t m2) {
    return 1e5 + static_cast<double>(2 * m1 + 1) * static_cast<double>(2 * m2 + 1);
  };
  const std::vector<FrequencyPiece> pieces = PartitionFrequencies(k, cost);
  EXPECT_EQ(pieces.size(), 4u);  // disk, 0, 90 and 30 degrees
  double cells = 0.0;
  for (const FrequencyPiece& piece : pieces) {
    cells += static_cast<double>(2 * piece.box.m1 + 1) * static_cast<double>(2 * piece.box.m2 + 1);
  }
  // All boxes together hold a small multiple of +-K.
  EXPECT_LT(cells, 4.0 * 2.0 * static_cast<double>(k.size()));
}

}  // namespace
}  // namespace alignset

namespace alignset {
namespace {

TEST(NufftLoopsTest, SelectedVariantAgreesWithGeneric) {
  const NufftLoops& fast = SelectedNufftLoops();
  const NufftLoops& generic = GenericNufftLoops();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double tol : {1e-5, 1e-9}) {
    const EsKernel kernel(tol);
    const int w = kernel.width();
    const int n1 = 40, n2 = 30;
    const size_t count = 37;  // not a multiple of the lane count
    std::vector<double> x1(count), x2(count);
    for (size_t i = 0; i < count; ++i) {
      x1[i] = u(rng) * n1;
      x2[i] = u(rng) * n2;
    }
    std::vector<double> ka(count * w), kb(count * w), k2(count * w);
    std::vector<int> ra(count), rb(count), col(count);
    fast.weights(kernel.coefficients(), kernel.degree(), w, x1.data(), count, n1, ka.data(),
                 ra.data());
    generic.weights(kernel.coefficients(), kernel.degree(), w, x1.data(), count, n1, kb.data(),
                    rb.data());
    fast.weights(kernel.coefficients(), kernel.degree(), w, x2.data(), count, n2, k2.data(),
                 col.data());
    for (size_t i = 0; i < count; ++i) {
      ASSERT_EQ(ra[i], rb[i]);
      double exact[EsKernel::kMaxWidth];
      const int first = kernel.ExactWeights(x1[i], exact);
      EXPECT_EQ(ra[i], ((first % n1) + n1) % n1);
      for (int t = 0; t < w; ++t) {
        EXPECT_NEAR(ka[i * w + t], kb[i * w + t], 1e-14);
        EXPECT_NEAR(ka[i * w + t], exact[t], 0.1 * tol);
      }
    }
    // Spread then interpolate on a padded grid: both variants agree.
    const size_t stride = n2 + w - 1, rows = n1 + w - 1;
    std::vector<double> ga(rows * stride, 0.0), gb(rows * stride, 0.0);
    fast.spread(ga.data(), stride, w, ka.data(), k2.data(), ra.data(), col.data(), count);
    generic.spread(gb.data(), stride, w, ka.data(), k2.data(), ra.data(), col.data(), count);
    double total = 0.0;
    for (size_t c = 0; c < ga.size(); ++c) {
      EXPECT_NEAR(ga[c], gb[c], 1e-13);
      total += ga[c];
    }
    // Each point spreads the product of its row and column weight sums.
    double want = 0.0;
    for (size_t i = 0; i < count; ++i) {
      double s1 = 0.0, s2 = 0.0;
      for (int t = 0; t < w; ++t) {
        s1 += ka[i * w + t];
        s2 += k2[i * w + t];
      }
      want += s1 * s2;
    }
    EXPECT_NEAR(total, want, 1e-11 * want);
    std::vector<std::complex<double>> cg(rows * stride);
    for (auto& c : cg) c = {u(rng), u(rng)};
    std::vector<std::complex<double>> oa(count), ob(count);
    fast.interpolate(cg.data(), stride, w, ka.data(), k2.data(), ra.data(), col.data(), count,
                     oa.data());
    generic.interpolate(cg.data(), stride, w, ka.data(), k2.data(), ra.data(), col.data(), count,
                        ob.data());
    for (size_t i = 0; i < count; ++i) EXPECT_LT(std::abs(oa[i] - ob[i]), 1e-13);
  }
}

// The interpolation of every width the loops are instantiated for (the AVX2
// variant holds its accumulators in registers, two (re, im) pairs each, with
// a half register left at odd widths) against the direct double sum over the
// width x width cells, in long double.
TEST(NufftLoopsTest, InterpolationIsTheDirectSumAtEveryWidth) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int w = 2; w <= EsKernel::kMaxWidth; ++w) {
    const size_t n1 = 23, n2 = 19, stride = n2 + w - 1, rows = n1 + w - 1;
    std::vector<std::complex<double>> grid(rows * stride);
    for (auto& c : grid) c = {u(rng), u(rng)};
    const size_t count = 29;
    std::vector<double> k1(count * w), k2(count * w);
    for (double& k : k1) k = u(rng);
    for (double& k : k2) k = u(rng);
    std::vector<int> row(count), col(count);
    for (size_t i = 0; i < count; ++i) {
      row[i] = static_cast<int>(rng() % n1);
      col[i] = static_cast<int>(rng() % n2);
    }
    for (const NufftLoops* loops : {&SelectedNufftLoops(), &GenericNufftLoops()}) {
      std::vector<std::complex<double>> out(count);
      loops->interpolate(grid.data(), stride, w, k1.data(), k2.data(), row.data(), col.data(),
                         count, out.data());
      for (size_t i = 0; i < count; ++i) {
        long double re = 0.0L, im = 0.0L, scale = 0.0L;
        for (int t1 = 0; t1 < w; ++t1) {
          for (int t2 = 0; t2 < w; ++t2) {
            const std::complex<double> g =
                grid[static_cast<size_t>(row[i] + t1) * stride + static_cast<size_t>(col[i] + t2)];
            const long double ab = static_cast<long double>(k1[i * w + t1]) * k2[i * w + t2];
            re += ab * g.real();
            im += ab * g.imag();
            scale += std::fabs(ab) * std::abs(g);
          }
        }
        EXPECT_NEAR(out[i].real(), static_cast<double>(re), 1e-14 * static_cast<double>(scale))
            << loops->isa << " width " << w << " point " << i;
        EXPECT_NEAR(out[i].imag(), static_cast<double>(im), 1e-14 * static_cast<double>(scale))
            << loops->isa << " width " << w << " point " << i;
      }
    }
  }
}

}  // namespace
}  // namespace alignset
