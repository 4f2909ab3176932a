#pragma once

#include <string>

#include "alignset/v1/alignset.pb.h"
#include "server/metrics.h"

namespace alignset::server {

// The Prometheus text exposition format (version 0.0.4) of what GetMetrics
// reports, plus the latency histograms, which GetMetrics does not carry.
// Every field of MetricsResponse appears, as alignset_<field>_total when it
// counts events and alignset_<field> when it is a level (queue length,
// waiting calls, uptime); a field without an entry here still appears, as an
// untyped sample, so a new counter is never silently left out.
// https://prometheus.io/docs/instrumenting/exposition_formats/
std::string PrometheusText(const v1::MetricsResponse& values, const Metrics& metrics);

}  // namespace alignset::server
