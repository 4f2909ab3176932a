#pragma once

#include <string>

#include "core/analysis/patch_spectrum.h"
#include "core/util/status.h"

namespace alignset::cli {

// An integrand patch, the input of `alignset direction` and
// `alignset get --from-patch`, by extension:
//   .npy  a grid of values, shape (H, W), float64 or float32, C or Fortran
//         order: rows along y, columns along x,
//         values[j, i] = f((i + 1/2) / W, (j + 1/2) / H), y growing with the
//         row index (NumPy's image layout, read as the unit square). A
//         transposed array turns theta into 90° - theta.
//   else  scattered samples, one "x y f" line each (x, y in [0, 1]); '#'
//         lines and blank lines are skipped. `-` reads them from stdin.
// Sizes, finite values and the limits are checked here with the core's own
// validators, so the CLI and the EstimateDirection RPC refuse the same input.
struct PatchInput {
  bool is_grid = false;
  GridPatch grid;        // when is_grid
  SampledPatch samples;  // otherwise
};

StatusOr<PatchInput> ReadPatchFile(const std::string& path);

}  // namespace alignset::cli
