#include "core/analysis/integrands.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/analysis/polygon_fourier.h"
#include "core/util/gauss_legendre.h"
#include "core/util/number_text.h"

namespace alignset {
namespace {

// The unit normal at `deg` as a ray (angles >= 180 flip it), so that
// step:210 is the complement of step:30.
Vec2 RayNormal(double deg) {
  const double rad = DegToRad(deg);
  Vec2 n = UnitVector(deg);
  if (std::abs(std::cos(rad) - n.x) > 1e-9 || std::abs(std::sin(rad) - n.y) > 1e-9) {
    n = {-n.x, -n.y};
  }
  return n;
}

std::string Degrees(double deg) {
  std::ostringstream s;
  s << deg << "deg";
  return s.str();
}

}  // namespace

PiecewiseLinearIntegrand::PiecewiseLinearIntegrand(std::string name, std::vector<Piece> pieces)
    : name_(std::move(name)), pieces_(std::move(pieces)) {
  for (const Piece& p : pieces_) {
    integral_ += IntegrateLinear(p.polygon, p.h);
    square_integral_ += IntegrateLinearSquared(p.polygon, p.h);
  }
}

double PiecewiseLinearIntegrand::Value(const Point2& p) const {
  for (const Piece& piece : pieces_) {
    if (ContainsPoint(piece.polygon, {p.x, p.y})) return piece.h({p.x, p.y});
  }
  return 0.0;
}

std::complex<double> PiecewiseLinearIntegrand::Fourier(int a, int b) const {
  std::complex<double> sum = 0.0;
  for (const Piece& piece : pieces_) {
    sum += LinearPolygonFourier(piece.polygon, piece.h, {static_cast<double>(a),
                                                         static_cast<double>(b)});
  }
  return sum;
}

DiskIntegrand::DiskIntegrand(Vec2 centre, double radius) : centre_(centre), radius_(radius) {}

std::string DiskIntegrand::name() const {
  std::ostringstream s;
  s << "disk r=" << radius_;
  return s.str();
}

double DiskIntegrand::Value(const Point2& p) const {
  // Torus distance: the periodized disk.
  double dx = std::abs(p.x - centre_.x), dy = std::abs(p.y - centre_.y);
  dx = std::min(dx, 1.0 - dx);
  dy = std::min(dy, 1.0 - dy);
  return dx * dx + dy * dy <= radius_ * radius_ ? 1.0 : 0.0;
}

double DiskIntegrand::Integral() const { return kPi * radius_ * radius_; }

std::complex<double> DiskIntegrand::Fourier(int a, int b) const {
  const double rho = std::hypot(static_cast<double>(a), static_cast<double>(b));
  if (rho == 0.0) return Integral();
  const double magnitude = radius_ * std::cyl_bessel_j(1.0, 2.0 * kPi * radius_ * rho) / rho;
  return std::polar(magnitude, -2.0 * kPi * (a * centre_.x + b * centre_.y));
}

SeparableIntegrand::SeparableIntegrand(Kind kind, double centre, double sigma)
    : kind_(kind), centre_(centre), sigma_(sigma) {
  if (kind_ == Kind::kCosine) {
    name_ = "cosine product";
    integral_ = 0.5;
    square_integral_ = 0.375;  // 1/4 + 2 (1/4)^2
    return;
  }
  std::ostringstream s;
  s << "gaussian sigma=" << sigma_;
  name_ = s.str();
  const double r2 = std::sqrt(2.0);
  integral_ = sigma_ * std::sqrt(kPi / 2.0) *
              (std::erf((1.0 - centre_) / (sigma_ * r2)) - std::erf(-centre_ / (sigma_ * r2)));
  square_integral_ = sigma_ * std::sqrt(kPi) / 2.0 *
                     (std::erf((1.0 - centre_) / sigma_) - std::erf(-centre_ / sigma_));
  // The 1-D coefficients g^(a) = integral_0^1 g(x) exp(-2 pi i a x) dx by
  // composite Gauss-Legendre: 1024 panels of 16 nodes resolve 8 periods per
  // panel at a = kMaxFrequency, where the rule is exact to ~1e-15 for this
  // entire function. Phases advance by a complex rotation per frequency and
  // are refreshed from sincos every kExactStride frequencies, so they stay
  // within a few dozen ulps.
  std::vector<double> t, w;
  GaussLegendre(16, &t, &w);
  constexpr int kPanels = 1024;
  constexpr int kExactStride = 32;
  std::vector<double> x, gw;
  for (int panel = 0; panel < kPanels; ++panel) {
    for (size_t i = 0; i < t.size(); ++i) {
      const double xi = (panel + 0.5 * (t[i] + 1.0)) / kPanels;
      x.push_back(xi);
      gw.push_back(0.5 * w[i] / kPanels * Profile(xi));
    }
  }
  std::vector<std::complex<double>> phase(x.size()), step(x.size());
  for (size_t i = 0; i < x.size(); ++i) step[i] = std::polar(1.0, -2.0 * kPi * x[i]);
  coefficients_.assign(kMaxFrequency + 1, 0.0);
  for (int a = 0; a <= kMaxFrequency; ++a) {
    std::complex<double> sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      if (a % kExactStride == 0) {
        const double ph = a * x[i];
        phase[i] = std::polar(1.0, -2.0 * kPi * (ph - std::floor(ph)));
      } else {
        phase[i] *= step[i];
      }
      sum += gw[i] * phase[i];
    }
    coefficients_[a] = sum;
  }
}

std::unique_ptr<SeparableIntegrand> SeparableIntegrand::ClippedGaussian(double centre,
                                                                        double sigma) {
  return std::unique_ptr<SeparableIntegrand>(new SeparableIntegrand(Kind::kGaussian, centre, sigma));
}

std::unique_ptr<SeparableIntegrand> SeparableIntegrand::CosineProduct() {
  return std::unique_ptr<SeparableIntegrand>(new SeparableIntegrand(Kind::kCosine, 0.5, 0.0));
}

double SeparableIntegrand::Profile(double x) const {
  if (kind_ == Kind::kCosine) return 0.5 * (1.0 + std::cos(2.0 * kPi * x));
  const double d = x - centre_;
  return std::exp(-d * d / (2.0 * sigma_ * sigma_));
}

std::complex<double> SeparableIntegrand::Coefficient1D(int a) const {
  if (kind_ == Kind::kCosine) {
    if (a == 0) return 0.5;
    return std::abs(a) == 1 ? 0.25 : 0.0;
  }
  if (std::abs(a) > kMaxFrequency) return 0.0;
  const std::complex<double> c = coefficients_[static_cast<size_t>(std::abs(a))];
  return a >= 0 ? c : std::conj(c);  // g real
}

std::complex<double> SeparableIntegrand::Fourier(int a, int b) const {
  return Coefficient1D(a) * Coefficient1D(b);
}

std::unique_ptr<PiecewiseLinearIntegrand> StepEdge(double normal_deg, double offset) {
  const Vec2 n = RayNormal(normal_deg);
  const double c = 0.5 * (n.x + n.y) + offset;
  std::vector<PiecewiseLinearIntegrand::Piece> pieces;
  Polygon p = ClipHalfPlane(UnitSquarePolygon(), n, c);
  if (!p.empty()) pieces.push_back({std::move(p), {1.0, {0.0, 0.0}}});
  return std::make_unique<PiecewiseLinearIntegrand>("step " + Degrees(normal_deg),
                                                    std::move(pieces));
}

std::unique_ptr<PiecewiseLinearIntegrand> SmoothedStep(double normal_deg, double width,
                                                       double offset) {
  const Vec2 n = RayNormal(normal_deg);
  const double c = 0.5 * (n.x + n.y) + offset;  // n.x = c on the edge line
  const double hw = 0.5 * width;
  std::vector<PiecewiseLinearIntegrand::Piece> pieces;
  Polygon full = ClipHalfPlane(UnitSquarePolygon(), n, c + hw);
  if (!full.empty()) pieces.push_back({std::move(full), {1.0, {0.0, 0.0}}});
  // Ramp: h = 1/2 + (n.x - c) / width on c - hw <= n.x < c + hw.
  Polygon ramp = ClipHalfPlane(ClipHalfPlane(UnitSquarePolygon(), n, c - hw), {-n.x, -n.y},
                               -(c + hw));
  if (!ramp.empty()) {
    pieces.push_back({std::move(ramp), {0.5 - c / width, {n.x / width, n.y / width}}});
  }
  std::ostringstream name;
  name << "smoothed step " << Degrees(normal_deg) << " w=" << width;
  return std::make_unique<PiecewiseLinearIntegrand>(name.str(), std::move(pieces));
}

std::unique_ptr<PiecewiseLinearIntegrand> PolygonIndicator(std::string name, Polygon polygon) {
  if (SignedArea(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  std::vector<PiecewiseLinearIntegrand::Piece> pieces;
  pieces.push_back({std::move(polygon), {1.0, {0.0, 0.0}}});
  return std::make_unique<PiecewiseLinearIntegrand>(std::move(name), std::move(pieces));
}

std::unique_ptr<PiecewiseLinearIntegrand> SquareBoundaryRamp() {
  std::vector<PiecewiseLinearIntegrand::Piece> pieces;
  pieces.push_back({UnitSquarePolygon(), {0.0, {0.5, 0.5}}});
  return std::make_unique<PiecewiseLinearIntegrand>("square boundary ramp (x+y)/2",
                                                    std::move(pieces));
}

namespace {

std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

}  // namespace

StatusOr<std::unique_ptr<Integrand>> MakeIntegrand(const std::string& spec) {
  const std::vector<std::string> parts = Split(spec, ':');
  const std::string& kind = parts[0];
  std::vector<double> args;
  for (size_t i = 1; i < parts.size(); ++i) {
    StatusOr<double> v = ParseFiniteDouble(parts[i], "integrand '" + spec + "'");
    if (!v.ok()) return v.status();
    args.push_back(*v);
  }
  auto arg = [&](size_t i, double fallback) { return i < args.size() ? args[i] : fallback; };
  auto arity = [&](size_t lo, size_t hi) -> Status {
    if (args.size() < lo || args.size() > hi) {
      return Status::InvalidArgument("integrand '" + spec + "': expected " + std::to_string(lo) +
                                     " to " + std::to_string(hi) + " numbers after '" + kind +
                                     "'");
    }
    return Status::Ok();
  };
  std::unique_ptr<Integrand> out;
  if (kind == "step") {
    if (Status s = arity(1, 2); !s.ok()) return s;
    out = StepEdge(args[0], arg(1, 0.0));
  } else if (kind == "smoothstep") {
    if (Status s = arity(1, 3); !s.ok()) return s;
    if (!(arg(1, 0.1) > 0.0)) return Status::InvalidArgument("smoothstep width must be > 0");
    out = SmoothedStep(args[0], arg(1, 0.1), arg(2, 0.0));
  } else if (kind == "disk") {
    if (args.size() != 0 && args.size() != 1 && args.size() != 3) {
      return Status::InvalidArgument("integrand '" + spec + "': expected disk[:R[:CX:CY]]");
    }
    if (!(arg(0, 0.3) > 0.0 && arg(0, 0.3) < 0.5)) {
      return Status::InvalidArgument("disk radius must be in (0, 0.5)");
    }
    out = std::make_unique<DiskIntegrand>(Vec2{arg(1, 0.5), arg(2, 0.5)}, arg(0, 0.3));
  } else if (kind == "triangle") {
    if (Status s = arity(0, 0); !s.ok()) return s;
    out = PolygonIndicator("triangle", {{0.2, 0.25}, {0.85, 0.4}, {0.35, 0.85}});
  } else if (kind == "polygon") {
    if (Status s = arity(1, 2); !s.ok()) return s;
    const int k = static_cast<int>(args[0]);
    if (k < 3 || k > 64 || k != args[0]) {
      return Status::InvalidArgument("polygon needs a whole number of edges in [3, 64]");
    }
    out = PolygonIndicator(std::to_string(k) + "-gon",
                           RegularPolygon({0.5, 0.5}, 0.35, k, arg(1, 0.0)));
  } else if (kind == "gaussian") {
    if (Status s = arity(0, 1); !s.ok()) return s;
    if (!(arg(0, 0.15) > 0.0)) return Status::InvalidArgument("gaussian sigma must be > 0");
    out = SeparableIntegrand::ClippedGaussian(0.5, arg(0, 0.15));
  } else if (kind == "product") {
    if (Status s = arity(0, 0); !s.ok()) return s;
    out = SeparableIntegrand::CosineProduct();
  } else if (kind == "boundary") {
    if (Status s = arity(0, 0); !s.ok()) return s;
    out = SquareBoundaryRamp();
  } else {
    return Status::InvalidArgument("unknown integrand '" + kind +
                                   "' (expected step, smoothstep, disk, triangle, polygon, "
                                   "gaussian, product or boundary)");
  }
  return out;
}

std::vector<std::string> IntegrandFamilySpecs(double theta_deg) {
  std::ostringstream t, t45;
  t << theta_deg;
  t45 << ReduceDirection(theta_deg + 45.0);
  return {"step:" + t.str(), "step:0",   "step:90",  "step:" + t45.str(), "smoothstep:" + t.str(),
          "disk",            "triangle", "gaussian", "product"};
}

}  // namespace alignset
