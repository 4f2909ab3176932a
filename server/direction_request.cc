#include "server/direction_request.h"

#include <string>

namespace alignset::server {
namespace {

void FillLobe(const DirectionLobe& lobe, v1::EstimatedDirection* out) {
  const bool found = lobe.status == DirectionStatus::kFound;
  out->set_status(found ? v1::DIRECTION_FOUND : v1::NO_DOMINANT_DIRECTION);
  out->set_theta_deg(found ? lobe.theta_deg : 0.0);
  out->set_kappa(lobe.kappa);
  out->set_confidence(lobe.confidence);
  out->set_contrast(lobe.contrast);
  out->set_reason(lobe.reason);
}

}  // namespace

StatusOr<DirectionInput> ParseDirectionRequest(const v1::EstimateDirectionRequest& request) {
  DirectionInput in;
  in.second = request.second();
  switch (request.input_case()) {
    case v1::EstimateDirectionRequest::kGrid: {
      const v1::ValueGrid& g = request.grid();
      // Sizes first, so that nothing is copied for a patch over the limit.
      if (Status s = ValidateGridSize(g.width(), g.height()); !s.ok()) return s;
      in.is_grid = true;
      in.grid.width = static_cast<int>(g.width());
      in.grid.height = static_cast<int>(g.height());
      in.grid.values.assign(g.values().begin(), g.values().end());
      if (Status s = ValidateGridPatch(in.grid); !s.ok()) return s;
      return in;
    }
    case v1::EstimateDirectionRequest::kSamples: {
      const v1::ScatteredSamples& s = request.samples();
      if (s.x_size() != s.y_size() || s.x_size() != s.f_size()) {
        return Status::InvalidArgument("samples need as many x as y and f, got " +
                                       std::to_string(s.x_size()) + ", " + std::to_string(s.y_size()) +
                                       " and " + std::to_string(s.f_size()));
      }
      if (s.x_size() > kMaxPatchSamples) {
        return Status::InvalidArgument("at most " + std::to_string(kMaxPatchSamples) +
                                       " samples, got " + std::to_string(s.x_size()));
      }
      in.is_grid = false;
      in.samples.points.resize(s.x_size());
      for (int j = 0; j < s.x_size(); ++j) in.samples.points[j] = {s.x(j), s.y(j)};
      in.samples.values.assign(s.f().begin(), s.f().end());
      if (Status st = ValidateSampledPatch(in.samples); !st.ok()) return st;
      return in;
    }
    default:
      return Status::InvalidArgument("give a grid of values or scattered samples");
  }
}

StatusOr<DirectionEstimate> RunDirectionEstimate(const DirectionInput& input) {
  DirectionOptions o;
  o.second = input.second;
  // One thread: the server runs requests concurrently.
  return input.is_grid ? EstimateDirection(input.grid, o) : EstimateDirection(input.samples, o);
}

void FillDirectionResponse(const DirectionEstimate& e, v1::EstimateDirectionResponse* out) {
  FillLobe(e.first, out->mutable_first());
  if (e.has_second) FillLobe(e.second, out->mutable_second());
  out->set_max_radius(e.max_radius);
}

}  // namespace alignset::server
