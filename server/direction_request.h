#pragma once

#include "alignset/v1/alignset.pb.h"
#include "core/analysis/direction_estimate.h"
#include "core/util/status.h"

namespace alignset::server {

// An EstimateDirection request checked and turned into the core's input:
// exactly one of a grid or samples, sizes that match, finite values, within
// the core's limits (core/analysis/patch_spectrum.h). Every refusal is
// INVALID_ARGUMENT with a one-line reason.
struct DirectionInput {
  bool is_grid = true;
  GridPatch grid;
  SampledPatch samples;
  bool second = false;
};
StatusOr<DirectionInput> ParseDirectionRequest(const v1::EstimateDirectionRequest& request);

// Runs the estimator on a parsed request.
StatusOr<DirectionEstimate> RunDirectionEstimate(const DirectionInput& input);

void FillDirectionResponse(const DirectionEstimate& estimate, v1::EstimateDirectionResponse* out);

}  // namespace alignset::server
