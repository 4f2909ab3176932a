#include "server/prometheus_text.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

namespace alignset::server {
namespace {

enum class Kind { kCounter, kGauge };

struct Meta {
  Kind kind;
  const char* help;
};

// The fields of MetricsResponse: what they are, in one line.
const std::map<std::string, Meta>& Fields() {
  static const std::map<std::string, Meta> fields = {
      {"requests_get", {Kind::kCounter, "GetAlignedSet calls (authorized)"}},
      {"requests_watch", {Kind::kCounter, "WatchAlignedSet calls (authorized)"}},
      {"requests_precompute", {Kind::kCounter, "Precompute calls (authorized)"}},
      {"requests_samples", {Kind::kCounter, "GetSamples calls (authorized)"}},
      {"requests_invalid", {Kind::kCounter, "calls refused as INVALID_ARGUMENT"}},
      {"cache_hits_memory", {Kind::kCounter, "sets served from the in-memory LRU"}},
      {"cache_hits_db", {Kind::kCounter, "sets read from SQLite"}},
      {"cache_misses", {Kind::kCounter, "sets not cached when asked for"}},
      {"corrupt_rows", {Kind::kCounter, "rows failing their checksum (recomputed)"}},
      {"optimizations_started", {Kind::kCounter, "optimizations started"}},
      {"optimizations_completed", {Kind::kCounter, "optimizations completed"}},
      {"optimizations_cancelled", {Kind::kCounter, "optimizations cancelled (nobody waiting)"}},
      {"optimizations_failed", {Kind::kCounter, "optimizations failed"}},
      {"shared_waits", {Kind::kCounter, "requests that joined an optimization already queued or running"}},
      {"queue_length", {Kind::kGauge, "optimizations waiting for a worker"}},
      {"running", {Kind::kGauge, "optimizations running on a worker"}},
      {"optimize_seconds_total", {Kind::kCounter, "seconds spent optimizing"}},
      {"optimize_seconds_max", {Kind::kGauge, "the longest optimization so far, in seconds"}},
      {"rejected_queue_full", {Kind::kCounter, "new jobs refused at --max-queue"}},
      {"uptime_seconds", {Kind::kGauge, "seconds since the server started"}},
      {"requests_unauthenticated", {Kind::kCounter, "calls refused for a missing or wrong token"}},
      {"sets_not_stored", {Kind::kCounter, "sets optimized and served but not written to the cache"}},
      {"rejected_client_limit", {Kind::kCounter, "new jobs refused at --max-queue-per-client"}},
      {"optimizations_paused", {Kind::kCounter, "slices that yielded their worker to another client"}},
      {"paused", {Kind::kGauge, "jobs waiting with a paused optimization state"}},
      {"waiting_calls", {Kind::kGauge, "GetAlignedSet / WatchAlignedSet calls waiting now"}},
      {"rejected_waiting_limit", {Kind::kCounter, "calls refused at --max-waiting-calls"}},
      {"database_integrity_errors",
       {Kind::kGauge, "problems PRAGMA quick_check found in the cache file (0: none)"}},
      {"requests_estimate", {Kind::kCounter, "EstimateDirection calls"}},
      {"read_only", {Kind::kGauge, "1 on a read-only replica (--read-only), 0 on a writer"}},
      {"replica_misses", {Kind::kCounter, "misses a read-only replica answered NOT_FOUND"}},
      {"sets_filled", {Kind::kCounter, "sets a replica got from its writer (--fill-from)"}},
      {"max_cache_bytes", {Kind::kGauge, "the cache file's bound (--max-cache-bytes; 0: none)"}},
      {"cache_evictions", {Kind::kCounter, "sets evicted from the cache file, least recently served first"}},
      {"cache_evicted_bytes", {Kind::kCounter, "bytes of the evicted sets in the file (estimated)"}},
      {"cache_file_bytes", {Kind::kGauge, "size of the cache file at the last look (bounded writers)"}},
      {"cache_vacuums", {Kind::kCounter, "background incremental vacuum passes"}},
      {"resident_bytes", {Kind::kGauge, "the process's resident memory (VmRSS)"}},
      {"heap_allocated_bytes", {Kind::kGauge, "malloc: bytes handed out and not yet freed (glibc)"}},
      {"heap_free_bytes", {Kind::kGauge, "malloc: freed bytes kept for reuse, not returned to the system"}},
      {"memory_cache_bytes", {Kind::kGauge, "decoded sets in the in-memory LRU"}},
      {"memory_cache_capacity_bytes", {Kind::kGauge, "the in-memory LRU's bound (--memory-cache-mb)"}},
      {"lattice_terms_bytes", {Kind::kGauge, "lattice search terms kept between keys"}},
      {"lattice_terms_capacity_bytes", {Kind::kGauge, "their bound (--lattice-terms-mb)"}},
      {"sqlite_memory_bytes", {Kind::kGauge, "SQLite's own allocations (page caches, statements)"}},
      {"sqlite_memory_peak_bytes", {Kind::kGauge, "SQLite's allocations at their highest since start"}},
      {"allocator", {Kind::kGauge, "the server's malloc (label allocator), always 1"}},
      {"resident_anonymous_bytes", {Kind::kGauge, "resident memory that is anonymous (heap, thread stacks)"}},
      {"resident_file_bytes", {Kind::kGauge, "resident memory backed by files (code, libraries, mapped files)"}},
  };
  return fields;
}

std::string Number(double v) {
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  if (std::isnan(v)) return "NaN";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

void Header(std::string* out, const std::string& name, const char* type, const std::string& help) {
  *out += "# HELP " + name + " " + help + "\n";
  *out += "# TYPE " + name + " " + type + "\n";
}

void AddHistogram(std::string* out, const std::string& name, const std::string& help,
                  const Histogram& h) {
  const Histogram::Snapshot s = h.Take();
  Header(out, name, "histogram", help);
  for (size_t i = 0; i < s.bounds.size(); ++i) {
    *out += name + "_bucket{le=\"" + Number(s.bounds[i]) + "\"} " + std::to_string(s.cumulative[i]) + "\n";
  }
  *out += name + "_bucket{le=\"+Inf\"} " + std::to_string(s.count) + "\n";
  *out += name + "_sum " + Number(s.sum) + "\n";
  *out += name + "_count " + std::to_string(s.count) + "\n";
}

}  // namespace

std::string PrometheusText(const v1::MetricsResponse& values, const Metrics& metrics) {
  using google::protobuf::FieldDescriptor;
  std::string out;
  const google::protobuf::Descriptor* d = values.GetDescriptor();
  const google::protobuf::Reflection* r = values.GetReflection();
  for (int i = 0; i < d->field_count(); ++i) {
    const FieldDescriptor* f = d->field(i);
    if (f->is_repeated()) continue;
    double v = 0.0;
    switch (f->cpp_type()) {
      case FieldDescriptor::CPPTYPE_UINT64: v = static_cast<double>(r->GetUInt64(values, f)); break;
      case FieldDescriptor::CPPTYPE_UINT32: v = r->GetUInt32(values, f); break;
      case FieldDescriptor::CPPTYPE_INT64: v = static_cast<double>(r->GetInt64(values, f)); break;
      case FieldDescriptor::CPPTYPE_INT32: v = r->GetInt32(values, f); break;
      case FieldDescriptor::CPPTYPE_DOUBLE: v = r->GetDouble(values, f); break;
      case FieldDescriptor::CPPTYPE_FLOAT: v = r->GetFloat(values, f); break;
      case FieldDescriptor::CPPTYPE_BOOL: v = r->GetBool(values, f) ? 1.0 : 0.0; break;
      case FieldDescriptor::CPPTYPE_STRING: {
        // A text (the allocator's name) is an info metric: the value in a label.
        std::string text = r->GetString(values, f);
        for (char& c : text) {
          if (c == '"' || c == '\\' || c == '\n') c = '_';
        }
        const std::string name = "alignset_" + f->name() + "_info";
        const auto meta = Fields().find(f->name());
        Header(&out, name, "gauge", meta == Fields().end() ? "MetricsResponse." + f->name() : meta->second.help);
        out += name + "{" + f->name() + "=\"" + text + "\"} 1\n";
        continue;
      }
      default: continue;
    }
    const auto meta = Fields().find(f->name());
    std::string name = "alignset_" + f->name();
    if (meta == Fields().end()) {
      Header(&out, name, "untyped", "MetricsResponse." + f->name());
    } else if (meta->second.kind == Kind::kCounter) {
      if (name.size() < 6 || name.compare(name.size() - 6, 6, "_total") != 0) name += "_total";
      Header(&out, name, "counter", meta->second.help);
    } else {
      Header(&out, name, "gauge", meta->second.help);
    }
    // Integer counts print exactly (up to 2^53, years of requests).
    out += name + " " + Number(v) + "\n";
  }
  Header(&out, "alignset_database_writable", "gauge",
         "1 when the start-up write probe of the cache succeeded, else 0");
  out += std::string("alignset_database_writable ") + (metrics.database_writable.load() ? "1" : "0") + "\n";
  Header(&out, "alignset_integrity_checks_total", "counter", "PRAGMA quick_check runs of the cache file");
  out += "alignset_integrity_checks_total " + std::to_string(metrics.integrity_checks.load()) + "\n";
  AddHistogram(&out, "alignset_get_latency_seconds",
               "GetAlignedSet calls from arrival to their end (set, error or cancel)", metrics.latency_get);
  AddHistogram(&out, "alignset_watch_latency_seconds", "WatchAlignedSet streams from arrival to their end",
               metrics.latency_watch);
  AddHistogram(&out, "alignset_precompute_latency_seconds", "Precompute streams from arrival to their end",
               metrics.latency_precompute);
  AddHistogram(&out, "alignset_samples_latency_seconds", "GetSamples calls", metrics.latency_samples);
  AddHistogram(&out, "alignset_optimization_seconds", "worker time of each optimization (its slices)",
               metrics.optimization_seconds);
  return out;
}

}  // namespace alignset::server
