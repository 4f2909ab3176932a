#include "server/server.h"

#include <grpc/grpc.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "server/active_calls.h"
#include "server/fill_client.h"
#include "server/integrity_watch.h"
#include "server/listen_address.h"
#include "server/metrics_http.h"
#include "server/prometheus_text.h"
#include "server/reflection_service.h"
#include "server/scheduler.h"
#include "server/service.h"
#include "server/tls_check.h"
#include "storage/paths.h"

namespace alignset::server {
namespace {

StatusOr<std::string> ReadFile(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::InvalidArgument(std::string("cannot read ") + what + " " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The token is the file's first line without surrounding white space.
StatusOr<std::string> ReadToken(const std::string& path) {
  auto text = ReadFile(path, "--token-file");
  if (!text.ok()) return text.status();
  std::string t = text->substr(0, text->find('\n'));
  const auto b = t.find_first_not_of(" \t\r");
  const auto e = t.find_last_not_of(" \t\r");
  t = b == std::string::npos ? "" : t.substr(b, e - b + 1);
  if (t.empty()) return Status::InvalidArgument("--token-file " + path + " holds no token");
  return t;
}

// "PORT\n", then "metrics PORT\n" when the metrics endpoint is on.
Status WritePortFile(const std::string& path, int port, int metrics_port) {
  const std::string tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) return Status::InvalidArgument("cannot write --port-file " + path);
  std::fprintf(f, "%d\n", port);
  if (metrics_port > 0) std::fprintf(f, "metrics %d\n", metrics_port);
  const bool ok = std::fclose(f) == 0;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    return Status::InvalidArgument("cannot write --port-file " + path);
  }
  return Status::Ok();
}

}  // namespace

struct ServerInstance::Impl {
  ServerConfig config;
  std::string db_path;
  Metrics metrics;
  std::unique_ptr<storage::SetCache> cache;
  std::unique_ptr<IntegrityWatch> integrity;
  std::unique_ptr<Scheduler> scheduler;
  std::unique_ptr<AlignSetService> service;
  std::unique_ptr<ReflectionService> reflection;
  std::unique_ptr<MetricsHttpServer> metrics_http;
  // Declared before the server, so destroyed after it: its calls' counters
  // point here.
  std::unique_ptr<ActiveCalls> active_calls = std::make_unique<ActiveCalls>();
  std::unique_ptr<grpc::Server> server;
  int port = 0;
  bool stopped = false;
};

ServerInstance::ServerInstance(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ServerInstance::~ServerInstance() { Shutdown(0.0); }

int ServerInstance::port() const { return impl_->port; }
const std::string& ServerInstance::db_path() const { return impl_->db_path; }

StatusOr<std::unique_ptr<ServerInstance>> ServerInstance::Start(const ServerConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  if (config.db_path.empty()) {
    auto p = storage::DefaultDatabasePath();
    if (!p.ok()) return p.status();
    impl->db_path = *p;
  } else {
    impl->db_path = config.db_path;
  }
  std::string token;
  if (!config.token_file.empty()) {
    auto t = ReadToken(config.token_file);
    if (!t.ok()) return t.status();
    token = *t;
  }
  std::shared_ptr<grpc::ServerCredentials> creds = grpc::InsecureServerCredentials();
  if (!config.tls_cert.empty()) {
    auto cert = ReadFile(config.tls_cert, "--tls-cert");
    if (!cert.ok()) return cert.status();
    auto key = ReadFile(config.tls_key, "--tls-key");
    if (!key.ok()) return key.status();
    if (Status s = CheckTlsKeyPair(*cert, *key, config.tls_cert, config.tls_key); !s.ok()) return s;
    grpc::SslServerCredentialsOptions ssl;
    ssl.pem_key_cert_pairs.push_back({*key, *cert});
    creds = grpc::SslServerCredentials(ssl);
  }

  storage::SetCache::Options cache_options;
  cache_options.immutable = config.read_only;
  auto cache = storage::SetCache::Open(impl->db_path, cache_options);
  if (!cache.ok()) return Status::Unavailable("cannot open the cache " + impl->db_path + ": " + cache.status().message());
  impl->cache = std::move(cache).value();
  impl->metrics.read_only.store(config.read_only);
  if (config.read_only) {
    // Not an alarm: a replica writes nothing by design.
    impl->metrics.database_writable.store(false);
  } else if (Status w = impl->cache->ProbeWrite(); !w.ok()) {
    impl->metrics.database_writable.store(false);
    spdlog::warn("the cache {} is not writable ({}): sets will be served but not stored, and "
                 "optimized again after a restart",
                 impl->db_path, w.message());
  }

  Scheduler::Options so;
  so.workers = config.workers;
  const unsigned cores = std::thread::hardware_concurrency();
  so.producer.threads_per_worker = ThreadsPerWorker(config.workers, config.threads_per_worker, cores);
  if (cores > 0 && config.workers * so.producer.threads_per_worker > static_cast<int>(cores)) {
    spdlog::warn("{} worker(s) x {} thread(s) oversubscribe the {} cores: optimizations will slow "
                 "each other down",
                 config.workers, so.producer.threads_per_worker, cores);
  }
  so.engine = config.engine;
  so.max_queue = config.max_queue;
  so.max_queue_per_client = config.max_queue_per_client;
  so.time_slice = std::chrono::milliseconds(config.time_slice_ms);
  so.max_paused = config.max_paused;
  so.producer.optimizer.max_iterations = config.max_iterations;
  so.producer.optimizer.warm_budget_fraction = config.warm_budget;
  so.producer.optimizer.warm_min_points = static_cast<uint32_t>(config.warm_min_n);
  so.producer.seed = config.seed;
  so.producer.memory_cache_bytes = static_cast<size_t>(config.memory_cache_mb) << 20;
  so.producer.lattice_terms_bytes = static_cast<size_t>(config.lattice_terms_mb) << 20;
  impl->integrity = std::make_unique<IntegrityWatch>(impl->db_path, &impl->metrics);
  so.producer.on_write_error = [w = impl->integrity.get()](const Status& s) { w->OnWriteError(s); };
  // A replica's shipped file was checked where it was made (`alignset cache
  // verify`); an immutable file cannot change under the server.
  if (config.quick_check && !config.read_only) impl->integrity->CheckInBackground("at start");
  so.producer.read_only = config.read_only;
  if (!config.fill_from.empty()) {
    std::string ca;
    if (!config.fill_tls_ca.empty()) {
      std::ifstream in(config.fill_tls_ca, std::ios::binary);
      std::ostringstream pem;
      pem << in.rdbuf();
      if (!in || pem.str().empty()) return Status::InvalidArgument("cannot read --fill-tls-ca " + config.fill_tls_ca);
      ca = pem.str();
    }
    so.producer.fill = MakeWriterFill(config.fill_from, token, config.fill_timeout_seconds, ca, config.fill_tls_name);
  }
  so.producer.max_cache_bytes = config.max_cache_bytes;
  // Beside the file it orders (a replica never evicts).
  if (config.max_cache_bytes > 0 && !config.read_only) so.producer.eviction_order_file = impl->db_path + ".served";
  auto scheduler = Scheduler::Create(so, impl->cache.get(), &impl->metrics);
  if (!scheduler.ok()) return scheduler.status();
  impl->scheduler = std::move(scheduler).value();
  impl->service = std::make_unique<AlignSetService>(config, impl->db_path, token, impl->cache.get(),
                                                    impl->scheduler.get(), &impl->metrics);

  AlignSetService* service = impl->service.get();
  impl->reflection = std::make_unique<ReflectionService>(
      std::vector<std::string>{v1::AlignSet::service_full_name(), "grpc.health.v1.Health",
                               "grpc.reflection.v1alpha.ServerReflection"},
      [service](grpc::ServerContext* ctx) { return service->Authorize(ctx); });

  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  // gRPC sets SO_REUSEPORT by default: a second server on the same address
  // would start without error and take part of the traffic, and with port 0
  // the listener it clones per poller binds a second, unreported port.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.AddListeningPort(config.listen, creds, &impl->port);
  builder.RegisterService(impl->service.get());
  builder.RegisterService(impl->reflection.get());
  {
    std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> counters;
    counters.push_back(impl->active_calls->InterceptorFactory());
    builder.experimental().SetInterceptorCreators(std::move(counters));
  }
  builder.SetMaxReceiveMessageSize(static_cast<int>(config.max_request_bytes));
  builder.SetMaxSendMessageSize(-1);
  impl->server = builder.BuildAndStart();
  if (!impl->server || impl->port == 0) {
    impl->scheduler->Shutdown();
    const std::string why = DescribeBindFailure(config.listen);
    return Status::Unavailable("cannot listen on " + config.listen + (why.empty() ? "" : ": " + why));
  }
  // The overall status ("") and the service's own name: probes and load
  // balancers ask per service.
  impl->server->GetHealthCheckService()->SetServingStatus(true);
  impl->server->GetHealthCheckService()->SetServingStatus(v1::AlignSet::service_full_name(), true);
  // The mode, for probes that ask: "alignset.read-only" is SERVING on a
  // replica and NOT_SERVING on a writer ("alignset.writer" the other way).
  impl->server->GetHealthCheckService()->SetServingStatus("alignset.read-only", config.read_only);
  impl->server->GetHealthCheckService()->SetServingStatus("alignset.writer", !config.read_only);
  if (!config.metrics_listen.empty()) {
    auto http = MetricsHttpServer::Start(config.metrics_listen, token, [service, m = &impl->metrics] {
      v1::MetricsResponse values;
      service->FillMetrics(&values);
      return PrometheusText(values, *m);
    }, &impl->metrics.requests_unauthenticated);
    if (!http.ok()) {
      impl->server->Shutdown();
      impl->scheduler->Shutdown();
      return http.status();
    }
    impl->metrics_http = std::move(http).value();
    spdlog::info("Prometheus metrics on http://{}/metrics (port {})", config.metrics_listen,
                 impl->metrics_http->port());
  }
  if (!config.port_file.empty()) {
    const int metrics_port = impl->metrics_http ? impl->metrics_http->port() : 0;
    if (Status s = WritePortFile(config.port_file, impl->port, metrics_port); !s.ok()) {
      impl->server->Shutdown();
      impl->scheduler->Shutdown();
      return s;
    }
  }
  if (!token.empty() && config.tls_cert.empty()) {
    spdlog::warn("--token-file without --tls-cert: the bearer token travels in clear text; "
                 "serve TLS or keep the listener on a trusted network");
  }
  spdlog::info("listening on {} (port {}), db {}{}, {} worker(s) x {} thread(s), engine {}, max n {}, "
               "max iterations {}{}{}",
               config.listen, impl->port, impl->db_path,
               config.read_only ? (config.fill_from.empty() ? " (read-only replica)"
                                                            : " (read-only replica, fills from " + config.fill_from + ")")
                                : (config.max_cache_bytes > 0
                                       ? " (bounded to " + std::to_string(config.max_cache_bytes) + " bytes)"
                                       : std::string()),
               config.workers,
               so.producer.threads_per_worker,
               EngineKindName(config.engine), config.max_n, config.max_iterations,
               config.tls_cert.empty() ? "" : ", TLS", token.empty() ? "" : ", bearer token");
  return std::unique_ptr<ServerInstance>(new ServerInstance(std::move(impl)));
}

void ServerInstance::Shutdown(double grace_seconds) {
  if (!impl_ || impl_->stopped) return;
  impl_->stopped = true;
  spdlog::info("shutting down (grace {:.1f} s)", grace_seconds);
  impl_->server->GetHealthCheckService()->SetServingStatus(false);
  // Waiting handlers see their jobs end and return; then the RPC layer drains.
  impl_->scheduler->BeginShutdown();
  const auto grace = std::chrono::milliseconds(static_cast<int64_t>(grace_seconds * 1000));
  const auto deadline = std::chrono::system_clock::now() + grace;
  const auto steady_deadline = std::chrono::steady_clock::now() + grace;
  // gRPC stops taking calls as soon as its shutdown begins and gives those
  // in flight until the deadline, then waits there for the clients'
  // connections to close, idle ones too (ActiveCalls says why): once the
  // calls are done, close what is left. A call counted as none were running
  // may have slipped in before gRPC's shutdown began: the check repeats
  // after a pause longer than that takes.
  std::thread stopper([&] { impl_->server->Shutdown(deadline); });
  while (impl_->active_calls->WaitUntilNone(steady_deadline)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (impl_->active_calls->count() == 0) break;
  }
  grpc_server_cancel_all_calls(impl_->server->c_server());
  stopper.join();
  impl_->server->Wait();
  impl_->scheduler->Shutdown();  // joins workers: a write in progress completes
  impl_->metrics_http.reset();  // before the service its scrapes read
  impl_->reflection.reset();
  impl_->service.reset();
  impl_->scheduler.reset();
  impl_->integrity.reset();  // waits for a check in progress
  impl_->cache.reset();  // closes SQLite cleanly (WAL checkpoint)
  spdlog::info("stopped");
}

}  // namespace alignset::server
