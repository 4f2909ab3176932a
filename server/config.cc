#include "server/config.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <vector>

#include "core/optimize/optimizer.h"
#include "core/util/number_text.h"
#include "server/listen_address.h"

namespace alignset::server {
namespace {

struct Flag {
  const char* name;
  const char* help;
  std::function<Status(ServerConfig&, const std::string&)> apply;
  // A switch: "--name" alone means 1 (also --name=0|1, and 0|1|true|false
  // from the environment).
  bool boolean = false;
};

template <typename T>
std::function<Status(ServerConfig&, const std::string&)> IntFlag(T ServerConfig::*field,
                                                                 const char* name, int64_t lo,
                                                                 int64_t hi) {
  return [=](ServerConfig& c, const std::string& v) {
    auto x = ParseInt(v, std::string("--") + name, lo, hi);
    if (!x.ok()) return x.status();
    c.*field = static_cast<T>(*x);
    return Status::Ok();
  };
}

std::function<Status(ServerConfig&, const std::string&)> StringFlag(std::string ServerConfig::*field) {
  return [=](ServerConfig& c, const std::string& v) {
    c.*field = v;
    return Status::Ok();
  };
}

const std::vector<Flag>& Flags() {
  static const std::vector<Flag> flags = {
      {"listen", "ADDR      address to listen on: HOST:PORT, [IPV6]:PORT or unix:PATH\n"
                 "                     (default 127.0.0.1:50051; port 0 picks one)",
       StringFlag(&ServerConfig::listen)},
      {"db", "PATH          SQLite cache (default $ALIGNSET_DATA_DIR or ~/.local/share/alignset)",
       StringFlag(&ServerConfig::db_path)},
      {"workers", "K       concurrent optimizations (default 1)",
       IntFlag(&ServerConfig::workers, "workers", 1, 256)},
      {"threads-per-worker", "T  CPU threads per optimization (default 0: the cores divided among the workers)",
       IntFlag(&ServerConfig::threads_per_worker, "threads-per-worker", 0, 1024)},
      {"max-n", "N         largest point count served (default 65536)",
       IntFlag(&ServerConfig::max_n, "max-n", kMinPoints, kMaxPoints)},
      {"max-iterations",
       "K  optimizer iterations per set (default 0: 1000 up to N = 4096, then growing like sqrt N;\n"
       "                     x1.5 for two directions)",
       IntFlag(&ServerConfig::max_iterations, "max-iterations", 0, 100000000)},
      {"warm-budget",
       "F  a key that is not a root of the key lineage continues from its parent's set for F\n"
       "                     times the iterations (default 0.13; 0: every key from Owen-Sobol)",
       [](ServerConfig& c, const std::string& v) {
         auto f = ParseFiniteDouble(v, "--warm-budget");
         if (!f.ok()) return f.status();
         if (!(*f >= 0.0 && *f <= 1.0)) {
           return Status::InvalidArgument("--warm-budget must be in [0, 1], got " + v);
         }
         c.warm_budget = *f;
         return Status::Ok();
       }},
      {"warm-min-n", "N   the smallest N whose keys use the key lineage (default 4096)",
       IntFlag(&ServerConfig::warm_min_n, "warm-min-n", kMinPoints, kMaxPoints)},
      {"engine", "E        spectral engine auto|direct|fast|cuda (default auto)",
       [](ServerConfig& c, const std::string& v) {
         auto k = ParseEngineKind(v);
         if (!k.ok()) return k.status();
         c.engine = *k;
         return Status::Ok();
       }},
      {"seed", "S          seed of the Owen-scrambled Sobol start (default 1)",
       IntFlag(&ServerConfig::seed, "seed", 0, INT64_MAX)},
      {"max-queue", "Q     optimizations allowed to wait (default 256)",
       IntFlag(&ServerConfig::max_queue, "max-queue", 1, 1000000)},
      {"max-queue-per-client", "Q  optimizations one client (connection) may have waiting (default 64)",
       IntFlag(&ServerConfig::max_queue_per_client, "max-queue-per-client", 1, 1000000)},
      {"time-slice-ms", "T    a running optimization yields to another client's waiting work\n"
                        "                     after T ms (default 500)",
       IntFlag(&ServerConfig::time_slice_ms, "time-slice-ms", 0, 3600000)},
      {"max-paused", "P      paused optimizations held in memory at once (default 16)",
       IntFlag(&ServerConfig::max_paused, "max-paused", 0, 100000)},
      {"max-waiting-calls", "W  GetAlignedSet/WatchAlignedSet calls that may wait at once (default 10000)",
       IntFlag(&ServerConfig::max_waiting_calls, "max-waiting-calls", 1, 10000000)},
      {"max-precompute-streams", "S  concurrent Precompute streams (default 4)",
       IntFlag(&ServerConfig::max_precompute_streams, "max-precompute-streams", 1, 1024)},
      {"max-batch-calls", "B  concurrent GetAlignedSets batches (default 16)",
       IntFlag(&ServerConfig::max_batch_calls, "max-batch-calls", 1, 1024)},
      {"quick-check", "0|1   check the cache file for damaged pages at start (default 1)",
       IntFlag(&ServerConfig::quick_check, "quick-check", 0, 1)},
      {"metrics-listen", "ADDR  serve Prometheus metrics on ADDR (HOST:PORT, GET /metrics; with --token-file\n                     it takes the same bearer token; default off)",
       StringFlag(&ServerConfig::metrics_listen)},
      {"read-only", "       serve the --db file read-only and immutable (a replica of a shipped cache):\n"
                    "                     never written; a miss is NOT_FOUND naming the key",
       [](ServerConfig& c, const std::string& v) {
         if (v == "1" || v == "true") {
           c.read_only = true;
         } else if (v == "0" || v == "false") {
           c.read_only = false;
         } else {
           return Status::InvalidArgument("--read-only: '" + v + "' is neither 0 nor 1");
         }
         return Status::Ok();
       },
       true},
      {"fill-from", "ADDR  with --read-only: ask the writer at ADDR (HOST:PORT) for a missing set;\n"
                    "                     its answer is kept in memory only",
       StringFlag(&ServerConfig::fill_from)},
      {"fill-tls-ca", "PEM with --fill-from: TLS to the writer, trusting this root certificate",
       StringFlag(&ServerConfig::fill_tls_ca)},
      {"fill-tls-name", "NAME with --fill-tls-ca: the name the writer's certificate must carry\n"
                        "                     (default: the host of --fill-from)",
       StringFlag(&ServerConfig::fill_tls_name)},
      {"max-cache-bytes", "B  bound the cache file: evict the least recently served sets (default 0: none)",
       IntFlag(&ServerConfig::max_cache_bytes, "max-cache-bytes", 0, INT64_MAX)},
      {"memory-cache-mb", "M  in-memory cache of decoded sets (default 512)",
       IntFlag(&ServerConfig::memory_cache_mb, "memory-cache-mb", 0, 1 << 20)},
      {"lattice-terms-mb", "M  the lattice search's terms kept between lattice keys (default 128; 0: none)",
       IntFlag(&ServerConfig::lattice_terms_mb, "lattice-terms-mb", 0, 1 << 20)},
      {"max-request-bytes", "B  largest request message (default 1048576)",
       IntFlag(&ServerConfig::max_request_bytes, "max-request-bytes", 1024, INT32_MAX)},
      {"tls-cert", "PEM    serve TLS with this certificate chain (needs --tls-key)",
       StringFlag(&ServerConfig::tls_cert)},
      {"tls-key", "PEM     private key of --tls-cert", StringFlag(&ServerConfig::tls_key)},
      {"token-file", "F   require 'authorization: Bearer <token>' with the token in F",
       StringFlag(&ServerConfig::token_file)},
      {"port-file", "F    write the bound port to F once listening",
       StringFlag(&ServerConfig::port_file)},
      {"log-level", "L    trace|debug|info|warn|error|off (default info)",
       StringFlag(&ServerConfig::log_level)},
      {"angle-step", "DEG  grid of one-direction requests: 0.25 (default, 181 keys) or 1 (46 keys)",
       [](ServerConfig& c, const std::string& v) {
         auto s = ParseFiniteDouble(v, "--angle-step");
         if (s.ok() && *s == 0.25) {
           c.angle_grid = AngleGrid::kQuarterDegree;
         } else if (s.ok() && *s == 1.0) {
           c.angle_grid = AngleGrid::kWholeDegree;
         } else {
           return Status::InvalidArgument("--angle-step: '" + v + "' is neither 0.25 nor 1");
         }
         return Status::Ok();
       }},
      {"shutdown-grace", "S  seconds running calls get after SIGTERM (default 5)",
       [](ServerConfig& c, const std::string& v) {
         auto s = ParseFiniteDouble(v, "--shutdown-grace");
         if (!s.ok() || *s < 0 || *s > 3600) {
           return Status::InvalidArgument("--shutdown-grace: '" + v + "' is not a number of seconds in [0, 3600]");
         }
         c.shutdown_grace_seconds = *s;
         return Status::Ok();
       }},
  };
  return flags;
}

std::string EnvName(const std::string& flag) {
  std::string e = "ALIGNSET_";
  for (char ch : flag) e.push_back(ch == '-' ? '_' : static_cast<char>(std::toupper(ch)));
  return e;
}

}  // namespace

std::string ServerUsage() {
  std::string u = "usage: alignset-server [options]\n\noptions (each also from the environment variable shown):\n";
  for (const Flag& f : Flags()) {
    u += "  --" + std::string(f.name) + " " + f.help + "  [" + EnvName(f.name) + "]\n";
  }
  u += "  -h, --help            this text\n"
       "  -V, --version         release, algorithm version and default profile id\n"
       "\nExit status: 0 after a clean stop (SIGTERM, SIGINT); 1 when the server cannot start\n"
       "(the address is taken, the cache cannot be opened); 2 usage (an unknown flag, a bad value).\n";
  return u;
}

StatusOr<ServerConfig> ParseServerConfig(int argc, char** argv, const EnvLookup& env) {
  ServerConfig config;
  const auto& flags = Flags();
  for (const Flag& f : flags) {
    if (!env) break;
    const std::string name = EnvName(f.name);
    if (const char* v = env(name.c_str()); v != nullptr && *v != '\0') {
      if (Status s = f.apply(config, v); !s.ok()) {
        return Status::InvalidArgument(name + ": " + s.message());
      }
    }
  }
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") return Status::NotFound(ServerUsage());
    if (a.rfind("--", 0) != 0) return Status::InvalidArgument("unexpected argument '" + a + "'");
    std::string name = a.substr(2), value;
    bool has_value = false;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    const Flag* flag = nullptr;
    for (const Flag& f : flags) {
      if (name == f.name) flag = &f;
    }
    if (flag == nullptr) return Status::InvalidArgument("unknown option --" + name + " (try --help)");
    if (!has_value && flag->boolean) {
      value = "1";
      has_value = true;
    }
    if (!has_value) {
      if (i + 1 >= argc) return Status::InvalidArgument("--" + name + " needs a value");
      value = argv[++i];
    }
    if (Status s = flag->apply(config, value); !s.ok()) return s;
  }
  if (config.tls_cert.empty() != config.tls_key.empty()) {
    return Status::InvalidArgument("--tls-cert and --tls-key go together");
  }
  if (config.listen.empty()) return Status::InvalidArgument("--listen is empty");
  if (auto a = ParseListenAddress(config.listen, "--listen"); !a.ok()) return a.status();
  if (!config.metrics_listen.empty()) {
    auto m = ParseListenAddress(config.metrics_listen, "--metrics-listen");
    if (!m.ok()) return m.status();
    if (m->unix_socket) return Status::InvalidArgument("--metrics-listen takes HOST:PORT");
  }
  if (!config.fill_from.empty()) {
    if (!config.read_only) return Status::InvalidArgument("--fill-from needs --read-only");
    auto f = ParseListenAddress(config.fill_from, "--fill-from");
    if (!f.ok()) return f.status();
  }
  if (config.fill_from.empty() && (!config.fill_tls_ca.empty() || !config.fill_tls_name.empty())) {
    return Status::InvalidArgument("--fill-tls-ca and --fill-tls-name go with --fill-from");
  }
  if (config.fill_tls_ca.empty() && !config.fill_tls_name.empty()) {
    return Status::InvalidArgument("--fill-tls-name needs --fill-tls-ca");
  }
  if (config.read_only && config.max_cache_bytes > 0) {
    return Status::InvalidArgument("--max-cache-bytes bounds a writer's file; a --read-only replica writes none");
  }
  if (config.max_cache_bytes > 0 && config.max_cache_bytes < (int64_t{1} << 16)) {
    return Status::InvalidArgument("--max-cache-bytes " + std::to_string(config.max_cache_bytes) +
                                   " is below 64 KiB (65536; the value is in bytes)");
  }
  return config;
}

int ThreadsPerWorker(int workers, int configured, unsigned cores) {
  if (configured > 0) return configured;
  const int c = std::max(1, static_cast<int>(cores));
  return std::max(1, c / std::max(1, workers));
}

}  // namespace alignset::server
