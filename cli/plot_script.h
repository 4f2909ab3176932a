#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::cli {

// PNG figures are drawn by one script, scripts/plot_analysis.py, with
// Debian's matplotlib: the C++ commands write their results as JSON and hand
// them to it, so a figure from `alignset analyze --png` and one from a bench
// script look the same and there is one plotting code path.
//
// The script is looked for at $ALIGNSET_PLOT_SCRIPT, then beside the
// installed binary (<prefix>/share/alignset/plot_analysis.py), then in the
// source tree the binary was built from; the interpreter is $ALIGNSET_PYTHON
// or /usr/bin/python3 (Debian's, which has python3-matplotlib).
StatusOr<std::string> FindPlotScript();

// Writes `json` to a temporary file and runs the script on it to make `png`.
// The script's own error lines pass through to stderr.
Status WritePlot(const std::string& json, const std::string& png);

}  // namespace alignset::cli
