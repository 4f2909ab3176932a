#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>

#include "core/spectral/direct_engine.h"

namespace alignset::server::testing {

// A gate the test opens and closes; engines wait at it before each evaluation,
// so a test can hold an optimization "running" for as long as it needs.
class Gate {
 public:
  void Open() {
    std::lock_guard<std::mutex> lock(mu_);
    open_ = true;
    cv_.notify_all();
  }
  void Close() {
    std::lock_guard<std::mutex> lock(mu_);
    open_ = false;
  }
  void Pass() {
    std::unique_lock<std::mutex> lock(mu_);
    ++arrivals_;
    cv_.notify_all();
    cv_.wait(lock, [&] { return open_; });
  }
  // Waits until some engine has reached the gate at least `n` times.
  void AwaitArrivals(int n) {
    std::unique_lock<std::mutex> lock(mu_);
    cv_.wait(lock, [&] { return arrivals_ >= n; });
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool open_ = true;
  int arrivals_ = 0;
};

class GatedEngine final : public SpectralEngine {
 public:
  explicit GatedEngine(std::shared_ptr<Gate> gate) : gate_(std::move(gate)), inner_(1) {}
  std::string name() const override { return "gated-direct"; }
  void SetFrequencies(const std::vector<Frequency>& k) override { inner_.SetFrequencies(k); }
  void SetLossWeights(std::vector<double> w) override { inner_.SetLossWeights(std::move(w)); }
  void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) override {
    gate_->Pass();
    inner_.Evaluate(points, with_gradient, out);
  }
  void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                        std::vector<std::complex<double>>* spectrum) override {
    inner_.EvaluateWeighted(points, strengths, spectrum);
  }

 private:
  std::shared_ptr<Gate> gate_;
  DirectEngine inner_;
};

}  // namespace alignset::server::testing
