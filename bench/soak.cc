// Soak test of alignset-server: mixed clients on loopback for a fixed time,
// one SIGKILL and restart of the server half way, then an integrity check.
//
//   alignset_soak --server-bin PATH --cli-bin PATH --work DIR --seconds S
//                 [--report FILE] [--kill-at 0.5] [--max-growth-mb 32]
//                 [--samples FILE]   (every 2 s sample, TSV, for plotting)
//
// It starts the server itself (fork/exec, 127.0.0.1 on a port it picks, a
// fresh cache in DIR), fills the N = 1024 one-direction space, and runs:
//   - 3 renderer-like clients: bursts of 16 GetAlignedSet cache hits (random
//     whole-degree directions at N = 1024; one client asks for its 16 in one
//     GetAlignedSets batch), a short pause, again;
//   - a new-key client: GetAlignedSet of two-direction N = 256 sets of random
//     realizations (mostly misses: an optimization each);
//   - a watcher: WatchAlignedSet of one-direction N = 512 sets, random
//     quarter degrees and realizations;
//   - a greedy client: Precompute of 46 x 64 keys at N = 2048, given up (its
//     deadline) after 15 s, and again;
//   - a cancelling client: GetAlignedSet of new N = 4096 keys with a 30 ms
//     deadline (DEADLINE_EXCEEDED expected; the abandoned job is dropped);
//   - a monitor: the server's resident memory and threads every 2 s
//     (/proc/PID/status), whether it is still alive, and where the memory is
//     (GetMetrics: malloc in use and kept free, the set LRU, lattice terms,
//     SQLite), so that growth can be put down to a part and its bound.
// At --kill-at of the run the server gets SIGKILL and is started again on
// the same port and file. Every set served is remembered by its request and
// a hash of its bytes: the same request must always get the same bytes. At
// the end: SIGTERM (exit 0 expected), `alignset cache verify` of the file,
// and a fresh server must serve every remembered set from the cache, byte
// for byte. Traffic goes to 127.0.0.1 only and is bounded by --seconds.
//
// Exit 0 when: zero lost and zero damaged sets, zero crashes (an exit the
// soak did not cause), verify clean, no unexpected error code (INTERNAL,
// DATA_LOSS, UNKNOWN, or a failed hit outside the restart window), and the
// resident memory after warm-up (the first 20% of the second server's life)
// grows by at most --max-growth-mb. The report (Markdown) says all figures.
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <alignset/client.h>
#include <cstdlib>

namespace {

using Clock = std::chrono::steady_clock;
using alignset::ServiceClient;
using alignset::Status;

struct Args {
  std::string server_bin, cli_bin, work, report, samples;
  double seconds = 120;
  double kill_at = 0.5;
  double max_growth_mb = 32;
};

uint64_t Fnv(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string CodeOf(const Status& s) {
  if (s.ok()) return "OK";
  const std::string& m = s.message();
  const auto colon = m.find(':');
  std::string code = colon == std::string::npos ? "" : m.substr(0, colon);
  if (code.empty() || code.find(' ') != std::string::npos) code = "client:" + s.ToString().substr(0, 20);
  return code;
}

int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  close(fd);
  return ntohs(a.sin_port);
}

struct Sample {
  double t;
  double rss_mb;
  int threads;
  int life;  // 1: the first server, 2: after the restart
  // From GetMetrics (MB; -1 when the call failed): malloc's bytes in use and
  // kept free, the set LRU, lattice terms, SQLite's own.
  double heap_mb = -1, free_mb = -1, lru_mb = -1, lattice_mb = -1, sqlite_mb = -1;
  double anon_mb = -1, file_mb = -1;  // RssAnon, RssFile of /proc/PID/status
};

// Least-squares slope of y over t, per hour.
double SlopePerHour(const std::vector<std::pair<double, double>>& ty) {
  if (ty.size() < 2) return 0;
  double st = 0, sy = 0;
  for (const auto& [t, y] : ty) st += t, sy += y;
  const double mt = st / ty.size(), my = sy / ty.size();
  double num = 0, den = 0;
  for (const auto& [t, y] : ty) num += (t - mt) * (y - my), den += (t - mt) * (t - mt);
  return den > 0 ? 3600.0 * num / den : 0;
}

class Soak {
 public:
  explicit Soak(Args a) : args_(std::move(a)) {}

  int Run();

 private:
  pid_t StartServer();
  bool WaitHealthy(double seconds);
  std::unique_ptr<ServiceClient> Connect(bool own) {
    alignset::ConnectOptions o;
    o.address = addr_;
    o.separate_connection = own;
    auto c = ServiceClient::Connect(o);
    if (!c.ok()) return nullptr;
    return std::move(c).value();
  }
  void Count(const char* client, const Status& s, bool hit_path);
  void Remember(const std::string& request, const std::string& raw);
  double Now() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  bool InRestartWindow() const {
    const double t = Now();
    return t >= kill_time_ - 0.5 && t <= restart_done_.load() + 2.0;
  }

  void HitClient(int id);
  void NewKeyClient();
  void Watcher();
  void Greedy();
  void Canceller();
  void Monitor();

  Args args_;
  std::string addr_;
  int port_ = 0;
  std::string db_;
  Clock::time_point t0_;
  double end_time_ = 0;
  double kill_time_ = 0;
  std::atomic<double> restart_done_{1e30};
  std::atomic<pid_t> pid_{0};
  std::atomic<bool> stop_{false};
  std::atomic<bool> killing_{false};
  std::atomic<int> crashes_{0};

  std::mutex mu_;
  std::map<std::string, std::map<std::string, uint64_t>> codes_;  // client -> code -> count
  std::vector<double> hit_latency_[2];                             // per server life, seconds
  std::vector<double> batch_latency_[2];                           // GetAlignedSets of 16 hits
  std::map<std::string, uint64_t> served_;                        // request -> hash of bytes
  uint64_t damaged_ = 0;
  uint64_t unexpected_ = 0;
  std::vector<Sample> samples_;
  std::unique_ptr<ServiceClient> metrics_client_;  // the monitor's own
  std::string allocator_;                          // as the server names it
};

pid_t Soak::StartServer() {
  const std::string listen = "127.0.0.1:" + std::to_string(port_);
  const std::string log = args_.work + "/server.log";
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::fopen(log.c_str(), "a");
    if (f != nullptr) {
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
    }
    execl(args_.server_bin.c_str(), args_.server_bin.c_str(), "--listen", listen.c_str(), "--db", db_.c_str(),
          "--max-iterations", "40", "--workers", "1", "--threads-per-worker", "1", "--memory-cache-mb", "16",
          "--log-level", "warn", "--shutdown-grace", "2", static_cast<char*>(nullptr));
    _exit(127);
  }
  pid_.store(pid);
  return pid;
}

bool Soak::WaitHealthy(double seconds) {
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < until) {
    if (auto c = Connect(true)) {
      alignset::CallOptions call;
      call.timeout_seconds = 1.0;
      if (auto h = c->Healthy(call); h.ok() && *h) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

void Soak::Count(const char* client, const Status& s, bool hit_path) {
  const std::string code = CodeOf(s);
  std::lock_guard<std::mutex> lock(mu_);
  ++codes_[client][code];
  const bool bad_anywhere = code == "INTERNAL" || code == "DATA_LOSS" || code == "UNKNOWN" ||
                            code == "INVALID_ARGUMENT" || code.rfind("client:", 0) == 0;
  if (bad_anywhere || (hit_path && !s.ok() && !InRestartWindow())) {
    ++unexpected_;
    std::fprintf(stderr, "soak: unexpected %s from %s at %.1f s: %s\n", code.c_str(), client, Now(),
                 s.message().c_str());
  }
}

void Soak::Remember(const std::string& request, const std::string& raw) {
  const uint64_t h = Fnv(raw);
  std::lock_guard<std::mutex> lock(mu_);
  auto [it, is_new] = served_.emplace(request, h);
  if (!is_new && it->second != h) {
    ++damaged_;
    std::fprintf(stderr, "soak: %s served different bytes at %.1f s\n", request.c_str(), Now());
  }
}

void Soak::HitClient(int id) {
  std::mt19937 rng(100 + id);
  std::uniform_int_distribution<int> dir(0, 179);
  auto c = Connect(true);
  while (!stop_) {
    if (id == 0) {  // a renderer that asks for its tile's 16 sets in one GetAlignedSets batch
      std::vector<alignset::SetRequest> items(16);
      std::vector<int> dirs(16);
      for (int i = 0; i < 16; ++i) {
        dirs[i] = dir(rng);
        items[i].n = 1024;
        items[i].directions_deg = {double(dirs[i])};
      }
      alignset::CallOptions call;
      call.timeout_seconds = 10.0;
      const auto t = Clock::now();
      auto b = c->GetAlignedSets(items, call);
      const double dt = std::chrono::duration<double>(Clock::now() - t).count();
      Count("hit-batches", b.status(), true);
      if (b.ok()) {
        for (int i = 0; i < 16; ++i) {
          Count("hit-batch-items", (*b)[i].status, true);
          if ((*b)[i].status.ok()) Remember("1024|" + std::to_string(dirs[i]) + "|r0", (*b)[i].set.raw);
        }
        std::lock_guard<std::mutex> lock(mu_);
        batch_latency_[Now() < kill_time_ ? 0 : 1].push_back(dt);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    for (int i = 0; i < 16 && !stop_; ++i) {
      const int d = dir(rng);
      alignset::CallOptions call;
      call.timeout_seconds = 10.0;
      const auto t = Clock::now();
      auto s = c->GetAlignedSet(1024, {double(d)}, call);
      const double dt = std::chrono::duration<double>(Clock::now() - t).count();
      Count("hits", s.status(), true);
      if (s.ok()) {
        Remember("1024|" + std::to_string(d) + "|r0", s->raw);
        std::lock_guard<std::mutex> lock(mu_);
        hit_latency_[Now() < kill_time_ ? 0 : 1].push_back(dt);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void Soak::NewKeyClient() {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> dir(0, 179), real(0, 63);
  auto c = Connect(true);
  while (!stop_) {
    int a = dir(rng), b = dir(rng);
    if (a == b) b = (b + 7) % 180;
    alignset::SetRequest r;
    r.n = 256;
    r.directions_deg = {double(a), double(b)};
    r.realization = real(rng);
    alignset::CallOptions call;
    call.timeout_seconds = 60.0;
    auto s = c->GetAlignedSet(r, call);
    Count("new-keys", s.status(), false);
    if (s.ok()) Remember("256|" + std::to_string(a) + "," + std::to_string(b) + "|r" + std::to_string(r.realization), s->raw);
    if (!s.ok()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

void Soak::Watcher() {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> quarter(0, 719), real(0, 63);
  auto c = Connect(true);
  while (!stop_) {
    alignset::SetRequest r;
    r.n = 512;
    const double d = quarter(rng) * 0.25;
    r.directions_deg = {d};
    r.steps_per_degree = 4;
    r.realization = real(rng);
    alignset::CallOptions call;
    call.timeout_seconds = 60.0;
    int updates = 0;
    auto s = c->WatchAlignedSet(r, [&](const alignset::WatchUpdate&) { ++updates; }, call);
    Count("watchers", s.status(), false);
    char key[64];
    std::snprintf(key, sizeof key, "512|%.2f|r%u", d, r.realization);
    if (s.ok()) Remember(key, s->raw);
    if (!s.ok()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

void Soak::Greedy() {
  auto c = Connect(true);
  while (!stop_) {
    alignset::PrecomputeSpec spec;
    spec.n = {2048};
    spec.space = 1;
    spec.realizations = 64;
    alignset::CallOptions call;
    call.timeout_seconds = std::min(15.0, std::max(1.0, end_time_ - Now()));
    auto s = c->Precompute(spec, [](const alignset::PrecomputeUpdate&) {}, call);
    Count("greedy-precompute", s.status(), false);
    if (!s.ok()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

void Soak::Canceller() {
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> dir(0, 179), real(1, 63);
  auto c = Connect(true);
  while (!stop_) {
    alignset::SetRequest r;
    r.n = 4096;
    r.directions_deg = {double(dir(rng))};
    r.steps_per_degree = 1;
    r.realization = real(rng);
    alignset::CallOptions call;
    call.timeout_seconds = 0.03;
    auto s = c->GetAlignedSet(r, call);
    Count("cancellers", s.status(), false);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

void Soak::Monitor() {
  while (!stop_) {
    const pid_t pid = pid_.load();
    if (!killing_) {
      int st = 0;
      if (waitpid(pid, &st, WNOHANG) == pid) {
        std::fprintf(stderr, "soak: the server exited by itself (status %d) at %.1f s\n", st, Now());
        ++crashes_;
        pid_.store(StartServer());
        WaitHealthy(30);
        continue;
      }
    }
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    double rss = -1, anon = -1, file = -1;
    int threads = -1;
    while (std::getline(in, line)) {
      if (line.rfind("VmRSS:", 0) == 0) rss = std::stod(line.substr(6)) / 1024.0;
      if (line.rfind("RssAnon:", 0) == 0) anon = std::stod(line.substr(8)) / 1024.0;
      if (line.rfind("RssFile:", 0) == 0) file = std::stod(line.substr(8)) / 1024.0;
      if (line.rfind("Threads:", 0) == 0) threads = std::stoi(line.substr(8));
    }
    if (rss >= 0) {
      Sample sample{Now(), rss, threads, Now() < kill_time_ ? 1 : 2};
      sample.anon_mb = anon;
      sample.file_mb = file;
      if (!killing_) {
        if (!metrics_client_) metrics_client_ = Connect(true);
        alignset::CallOptions call;
        call.timeout_seconds = 1.0;
        auto m = metrics_client_ ? metrics_client_->GetMetrics(call)
                                 : alignset::StatusOr<alignset::ServiceMetrics>(Status::Unavailable("no client"));
        if (m.ok()) {
          constexpr double kMB = 1048576.0;
          sample.heap_mb = m->heap_allocated_bytes / kMB;
          sample.free_mb = m->heap_free_bytes / kMB;
          sample.lru_mb = m->memory_cache_bytes / kMB;
          sample.lattice_mb = m->lattice_terms_bytes / kMB;
          sample.sqlite_mb = m->sqlite_memory_bytes / kMB;
          if (allocator_.empty()) allocator_ = m->allocator;
        } else {
          metrics_client_.reset();  // a new connection after a restart
        }
      }
      std::lock_guard<std::mutex> lock(mu_);
      samples_.push_back(sample);
    }
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * v.size()))];
}

int Soak::Run() {
  db_ = args_.work + "/soak.sqlite";
  std::remove(db_.c_str());
  std::remove((db_ + "-wal").c_str());
  std::remove((db_ + "-shm").c_str());
  port_ = FreePort();
  addr_ = "127.0.0.1:" + std::to_string(port_);
  t0_ = Clock::now();
  end_time_ = args_.seconds;
  kill_time_ = args_.seconds * args_.kill_at;
  StartServer();
  if (!WaitHealthy(30)) {
    std::fprintf(stderr, "soak: the server did not start (log %s/server.log)\n", args_.work.c_str());
    return 1;
  }
  {  // the renderer's space: 46 sets
    auto c = Connect(true);
    alignset::PrecomputeSpec spec;
    spec.n = {1024};
    auto s = c->Precompute(spec, [](const alignset::PrecomputeUpdate&) {});
    if (!s.ok()) {
      std::fprintf(stderr, "soak: filling the N = 1024 space: %s\n", s.status().message().c_str());
      return 1;
    }
  }
  const double fill_seconds = Now();
  std::vector<std::thread> threads;
  for (int i = 0; i < 3; ++i) threads.emplace_back([this, i] { HitClient(i); });
  threads.emplace_back([this] { NewKeyClient(); });
  threads.emplace_back([this] { Watcher(); });
  threads.emplace_back([this] { Greedy(); });
  threads.emplace_back([this] { Canceller(); });
  threads.emplace_back([this] { Monitor(); });

  double down_seconds = 0;
  while (Now() < kill_time_) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  {
    killing_ = true;
    const pid_t pid = pid_.load();
    const double t = Now();
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    StartServer();
    killing_ = false;
    if (!WaitHealthy(60)) {
      std::fprintf(stderr, "soak: the server did not come back after SIGKILL\n");
      stop_ = true;
      for (auto& th : threads) th.join();
      return 1;
    }
    restart_done_.store(Now());
    down_seconds = Now() - t;
  }
  while (Now() < end_time_) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  stop_ = true;
  for (auto& th : threads) th.join();

  // The end: SIGTERM, verify the file, then every set again from a fresh server.
  killing_ = true;
  int st = 0;
  kill(pid_.load(), SIGTERM);
  waitpid(pid_.load(), &st, 0);
  const bool clean_exit = WIFEXITED(st) && WEXITSTATUS(st) == 0;
  if (!clean_exit) ++crashes_;
  const std::string verify_cmd = args_.cli_bin + " cache verify --db " + db_ + " > " + args_.work + "/verify.txt 2>&1";
  const int verify_rc = std::system(verify_cmd.c_str());
  std::string verify_text;
  {
    std::ifstream in(args_.work + "/verify.txt");
    std::getline(in, verify_text);
  }
  StartServer();
  uint64_t lost = 0, checked = 0;
  if (!WaitHealthy(30)) {
    lost = served_.size();
  } else {
    auto c = Connect(true);
    for (const auto& [request, hash] : served_) {
      // "n|dirs|rR"
      const auto p1 = request.find('|'), p2 = request.rfind('|');
      alignset::SetRequest r;
      r.n = static_cast<uint32_t>(std::stoul(request.substr(0, p1)));
      std::stringstream dirs(request.substr(p1 + 1, p2 - p1 - 1));
      std::string d;
      while (std::getline(dirs, d, ',')) r.directions_deg.push_back(std::stod(d));
      r.realization = static_cast<uint32_t>(std::stoul(request.substr(p2 + 2)));
      r.steps_per_degree = r.n == 512 ? 4 : 1;
      alignset::CallOptions call;
      call.timeout_seconds = 10.0;
      auto s = c->GetAlignedSet(r, call);
      ++checked;
      if (!s.ok() || !s->info.from_cache) {
        ++lost;
        std::fprintf(stderr, "soak: lost %s (%s)\n", request.c_str(),
                     s.ok() ? "optimized again" : s.status().message().c_str());
      } else if (Fnv(s->raw) != hash) {
        ++damaged_;
        std::fprintf(stderr, "soak: %s came back different\n", request.c_str());
      }
    }
  }
  kill(pid_.load(), SIGTERM);
  waitpid(pid_.load(), &st, 0);
  if (!(WIFEXITED(st) && WEXITSTATUS(st) == 0)) ++crashes_;

  // Memory after warm-up: the second server's life, its first 20% left out.
  const double warm = restart_done_.load() + 0.2 * (end_time_ - restart_done_.load());
  double base = -1, last = -1, peak = 0;
  int tmin = 1 << 30, tmax = 0;
  for (const Sample& s : samples_) {
    if (s.life != 2 || s.t < warm) continue;
    if (base < 0) base = s.rss_mb;
    last = s.rss_mb;
    peak = std::max(peak, s.rss_mb);
    tmin = std::min(tmin, s.threads);
    tmax = std::max(tmax, s.threads);
  }
  const double growth = base < 0 ? 0 : peak - base;
  // Each part's first, peak, last and trend after warm-up (metrics samples).
  struct Part {
    const char* name;
    double Sample::*field;
    double first = -1, peak = 0, last = -1;
    std::vector<std::pair<double, double>> ty = {};
  };
  std::vector<Part> parts = {{"resident (VmRSS)", &Sample::rss_mb},
                             {"resident anonymous (RssAnon: heap, stacks)", &Sample::anon_mb},
                             {"resident files (RssFile: code, libraries, SQLite -shm)", &Sample::file_mb},
                             {"malloc in use", &Sample::heap_mb},
                             {"allocator kept, not in use", &Sample::free_mb},
                             {"set LRU (--memory-cache-mb 16)", &Sample::lru_mb},
                             {"lattice terms", &Sample::lattice_mb},
                             {"SQLite", &Sample::sqlite_mb}};
  for (Part& p : parts) {
    for (const Sample& s : samples_) {
      const double v = s.*p.field;
      if (s.life != 2 || s.t < warm || v < 0) continue;
      if (p.first < 0) p.first = v;
      p.last = v;
      p.peak = std::max(p.peak, v);
      p.ty.emplace_back(s.t, v);
    }
  }
  const bool memory_ok = base >= 0 && growth <= args_.max_growth_mb;
  const bool ok = lost == 0 && damaged_ == 0 && crashes_ == 0 && verify_rc == 0 && unexpected_ == 0 && memory_ok;

  std::ostringstream r;
  r << "# alignset soak: " << args_.seconds << " s of mixed clients on loopback\n\n";
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Machine: %u cores visible, load average at the end %s. Server: 1 worker x 1 thread, "
                "--max-iterations 40, --memory-cache-mb 16 (so that the in-memory LRU is full early and memory can be flat). Fill of the N = 1024 space: %.1f s.\n\n",
                std::thread::hardware_concurrency(), [] {
                  std::ifstream in("/proc/loadavg");
                  std::string l;
                  std::getline(in, l);
                  return l.substr(0, 14);
                }().c_str(), fill_seconds);
  r << buf;
  r << "## Result: " << (ok ? "PASS" : "FAIL") << "\n\n";
  r << "| check | figure |\n|---|---|\n";
  r << "| sets remembered (distinct requests served) | " << served_.size() << " |\n";
  r << "| lost (not served from the cache at the end) | " << lost << " of " << checked << " |\n";
  r << "| damaged (other bytes for the same request) | " << damaged_ << " |\n";
  r << "| crashes (exits the soak did not cause, unclean stops) | " << crashes_.load() << " |\n";
  r << "| `alignset cache verify` | exit " << (verify_rc == 0 ? 0 : 1) << ": " << verify_text << " |\n";
  r << "| unexpected errors | " << unexpected_ << " |\n";
  std::snprintf(buf, sizeof buf, "| SIGKILL at %.1f s, serving again after | %.2f s |\n", kill_time_, down_seconds);
  r << buf;
  std::snprintf(buf, sizeof buf,
                "| resident memory after warm-up (from %.0f s): first, peak, last | %.1f, %.1f, %.1f MB "
                "(growth %.1f MB, bound %.0f) |\n",
                warm, base, peak, last, growth, args_.max_growth_mb);
  r << buf;
  r << "| server threads after warm-up: min, max | " << tmin << ", " << tmax << " |\n";
  r << "| the server's allocator (GetMetrics) | " << (allocator_.empty() ? "not reported" : allocator_) << " |\n\n";
  r << "## Where the memory is after warm-up (GetMetrics every 2 s)\n\n"
       "| part | first MB | peak MB | last MB | trend MB/h (least squares) |\n|---|---:|---:|---:|---:|\n";
  for (const Part& p : parts) {
    std::snprintf(buf, sizeof buf, "| %s | %.1f | %.1f | %.1f | %+.2f |\n", p.name, p.first, p.peak, p.last,
                  SlopePerHour(p.ty));
    r << buf;
  }
  r << "\n";
  r << "## Cache-hit latency (N = 1024: 2 renderer clients with bursts of 16 GetAlignedSet calls, one with GetAlignedSets batches of 16)\n\n";
  auto latency_table = [&](const char* what, const std::vector<double>* lives) {
    r << "| server | " << what << " | p50 ms | p99 ms | max ms |\n|---|---:|---:|---:|---:|\n";
    for (int l = 0; l < 2; ++l) {
      std::snprintf(buf, sizeof buf, "| %s | %zu | %.3f | %.3f | %.3f |\n", l == 0 ? "before SIGKILL" : "after restart",
                    lives[l].size(), 1e3 * Percentile(lives[l], 0.5), 1e3 * Percentile(lives[l], 0.99),
                    1e3 * Percentile(lives[l], 1.0));
      r << buf;
    }
  };
  latency_table("hits (GetAlignedSet)", hit_latency_);
  r << "\n";
  latency_table("batches of 16 hits (GetAlignedSets)", batch_latency_);
  r << "\n## Calls by client and status code\n\n| client | code | calls |\n|---|---|---:|\n";
  for (const auto& [client, m] : codes_) {
    for (const auto& [code, n] : m) r << "| " << client << " | " << code << " | " << n << " |\n";
  }
  r << "\nExpected non-OK codes: DEADLINE_EXCEEDED (the cancelling client's 30 ms deadline, the greedy "
       "client's 15 s one), UNAVAILABLE around the restart, RESOURCE_EXHAUSTED (queue bounds).\n";
  r << "\n## Server memory and threads over time (every 2 s; shown every ~" << std::max<size_t>(1, samples_.size() / 30) * 2
    << " s)\n\n| t s | server | RSS MB | anonymous | files | allocated | kept | set LRU | SQLite | threads |\n"
       "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const size_t step = std::max<size_t>(1, samples_.size() / 30);
  for (size_t i = 0; i < samples_.size(); i += step) {
    const Sample& s = samples_[i];
    std::snprintf(buf, sizeof buf, "| %.0f | %d | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %d |\n", s.t, s.life,
                  s.rss_mb, s.anon_mb, s.file_mb, s.heap_mb, s.free_mb, s.lru_mb, s.sqlite_mb, s.threads);
    r << buf;
  }
  if (!args_.samples.empty()) {
    std::ofstream out(args_.samples);
    out << "t_s\tlife\trss_mb\tanon_mb\tfile_mb\theap_mb\tfree_mb\tlru_mb\tlattice_mb\tsqlite_mb\tthreads\n";
    for (const Sample& s : samples_) {
      out << s.t << "\t" << s.life << "\t" << s.rss_mb << "\t" << s.anon_mb << "\t" << s.file_mb << "\t" << s.heap_mb
          << "\t" << s.free_mb << "\t" << s.lru_mb << "\t" << s.lattice_mb << "\t" << s.sqlite_mb << "\t"
          << s.threads << "\n";
    }
  }
  const std::string text = r.str();
  std::fputs(text.c_str(), stdout);
  if (!args_.report.empty()) {
    std::ofstream out(args_.report);
    out << text;
  }
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--server-bin") a.server_bin = v;
    else if (k == "--cli-bin") a.cli_bin = v;
    else if (k == "--work") a.work = v;
    else if (k == "--report") a.report = v;
    else if (k == "--samples") a.samples = v;
    else if (k == "--seconds") a.seconds = std::stod(v);
    else if (k == "--kill-at") a.kill_at = std::stod(v);
    else if (k == "--max-growth-mb") a.max_growth_mb = std::stod(v);
    else {
      std::fprintf(stderr, "alignset_soak: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  if (a.server_bin.empty() || a.cli_bin.empty() || a.work.empty()) {
    std::fprintf(stderr, "usage: alignset_soak --server-bin PATH --cli-bin PATH --work DIR --seconds S "
                         "[--report FILE] [--kill-at 0.5] [--max-growth-mb 32]\n");
    return 2;
  }
  signal(SIGPIPE, SIG_IGN);
  Soak soak(a);
  return soak.Run();
}
