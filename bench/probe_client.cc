// Probes alignset-server the way issue 16's outside probe did, and prints
// the figures the README reports. Talks to the server through raw stubs of
// the wire contract only, so it also runs against older servers (that is how
// the "before" figures were taken). Three modes:
//
//   alignset_probe_client waiting --server ADDR --server-pid PID [--calls 2000]
//                         [--n 65536] [--dir 30]
//     opens `calls` GetAlignedSet calls on one connection, all for one key
//     that is being optimized, and prints the server's threads and resident
//     memory (from /proc/PID/status) before and while they wait.
//
//   alignset_probe_client watch --server ADDR [--n 65536] [--dir 21] [--seconds 20]
//     watches one optimization and prints the events per second and the
//     longest silence.
//
//   alignset_probe_client greedy --server ADDR [--greedy 50] [--greedy-n 32768]
//                         [--precompute-n 32768] [--victims 5] [--victim-n 256]
//                         [--deadline 60]
//     a greedy connection runs a precompute of the 4141 two-direction keys,
//     and then holds `greedy` more optimizations at N >= greedy-n; a second
//     connection's requests for small new sets ("victims") are timed, first
//     with only the precompute running, then with everything queued. Each
//     victim's wait is its latency minus its own optimization time (which the
//     server reports).
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "alignset/v1/alignset.grpc.pb.h"

namespace {

using namespace alignset;
using Clock = std::chrono::steady_clock;

std::map<std::string, std::string> ParseFlags(int argc, char** argv) {
  std::map<std::string, std::string> f;
  for (int i = 0; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    if (k.rfind("--", 0) != 0) {
      std::fprintf(stderr, "alignset_probe_client: expected --flag value, got '%s'\n", argv[i]);
      std::exit(2);
    }
    f[k.substr(2)] = argv[i + 1];
  }
  return f;
}

std::string Flag(const std::map<std::string, std::string>& f, const std::string& k, const std::string& def) {
  auto it = f.find(k);
  return it == f.end() ? def : it->second;
}

std::shared_ptr<grpc::Channel> OwnChannel(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(-1);
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);  // a connection of its own
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
}

v1::AlignedSetRequest Request(uint32_t n, std::vector<double> dirs) {
  v1::AlignedSetRequest r;
  r.set_n(n);
  for (double d : dirs) r.add_directions_deg(d);
  return r;
}

v1::MetricsResponse Metrics(v1::AlignSet::Stub& stub) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  v1::MetricsResponse m;
  stub.GetMetrics(&ctx, v1::MetricsRequest(), &m);
  return m;
}

std::pair<long, long> ThreadsAndRssKb(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  long threads = -1, rss = -1;
  while (in >> key) {
    if (key == "Threads:") in >> threads;
    if (key == "VmRSS:") in >> rss;
    in.ignore(1 << 20, '\n');
  }
  return {threads, rss};
}

// Unary GetAlignedSet calls in flight on one completion queue.
class AsyncCalls {
 public:
  explicit AsyncCalls(v1::AlignSet::Stub* stub) : stub_(stub) {}
  ~AsyncCalls() { CancelAndDrain(); }
  void Start(const v1::AlignedSetRequest& req) {
    auto c = std::make_unique<Call>();
    c->reader = stub_->PrepareAsyncGetAlignedSet(&c->ctx, req, &cq_);
    c->reader->StartCall();
    c->reader->Finish(&c->resp, &c->status, c.get());
    calls_.push_back(std::move(c));
  }
  size_t size() const { return calls_.size(); }
  void CancelAndDrain() {
    if (drained_) return;
    drained_ = true;
    for (auto& c : calls_) c->ctx.TryCancel();
    void* tag;
    bool ok;
    for (size_t i = 0; i < calls_.size(); ++i) cq_.Next(&tag, &ok);
    calls_.clear();
    cq_.Shutdown();
    while (cq_.Next(&tag, &ok)) {
    }
  }

 private:
  struct Call {
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    grpc::Status status;
    std::unique_ptr<grpc::ClientAsyncResponseReader<v1::AlignedSetResponse>> reader;
  };
  v1::AlignSet::Stub* stub_;
  grpc::CompletionQueue cq_;
  std::vector<std::unique_ptr<Call>> calls_;
  bool drained_ = false;
};

int Waiting(const std::map<std::string, std::string>& f) {
  const std::string address = Flag(f, "server", "127.0.0.1:50051");
  const int pid = std::stoi(Flag(f, "server-pid", "0"));
  const int calls = std::stoi(Flag(f, "calls", "2000"));
  const uint32_t n = static_cast<uint32_t>(std::stoul(Flag(f, "n", "65536")));
  const double dir = std::stod(Flag(f, "dir", "30"));
  auto stub = v1::AlignSet::NewStub(OwnChannel(address));
  const uint64_t get_before = Metrics(*stub).requests_get();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const auto [threads0, rss0] = ThreadsAndRssKb(pid);
  AsyncCalls waiting(stub.get());
  for (int i = 0; i < calls; ++i) waiting.Start(Request(n, {dir}));
  // Wait until the server has taken every call, then let it settle.
  const auto t0 = Clock::now();
  while (Metrics(*stub).requests_get() < get_before + calls && Clock::now() - t0 < std::chrono::seconds(60)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const uint64_t taken = Metrics(*stub).requests_get() - get_before;
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const auto [threads1, rss1] = ThreadsAndRssKb(pid);
  std::printf("waiting_calls %d (server took %llu)\n", calls, static_cast<unsigned long long>(taken));
  std::printf("threads_before %ld\nthreads_waiting %ld\nrss_kb_before %ld\nrss_kb_waiting %ld\n"
              "rss_added_mb %.1f\n",
              threads0, threads1, rss0, rss1, (rss1 - rss0) / 1024.0);
  return 0;
}

int Watch(const std::map<std::string, std::string>& f) {
  const std::string address = Flag(f, "server", "127.0.0.1:50051");
  const uint32_t n = static_cast<uint32_t>(std::stoul(Flag(f, "n", "65536")));
  const double dir = std::stod(Flag(f, "dir", "21"));
  const double seconds = std::stod(Flag(f, "seconds", "20"));
  auto stub = v1::AlignSet::NewStub(OwnChannel(address));
  grpc::ClientContext ctx;
  auto reader = stub->WatchAlignedSet(&ctx, Request(n, {dir}));
  std::atomic<bool> stop{false};
  std::thread timer([&] {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (!stop && Clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ctx.TryCancel();
  });
  const auto t0 = Clock::now();
  std::vector<double> at;
  int progress = 0, queued = 0, last_iteration = 0;
  v1::WatchEvent ev;
  while (reader->Read(&ev)) {
    at.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    progress += ev.has_progress();
    queued += ev.has_queued();
    if (ev.has_progress()) last_iteration = ev.progress().iteration();
  }
  stop = true;
  timer.join();
  reader->Finish();
  double gap = at.empty() ? seconds : at.front();
  for (size_t i = 1; i < at.size(); ++i) gap = std::max(gap, at[i] - at[i - 1]);
  if (!at.empty()) gap = std::max(gap, seconds - at.back());
  std::printf("n %u seconds %.1f events %zu progress %d queued %d events_per_second %.2f "
              "longest_silence_s %.2f last_iteration %d\n",
              n, seconds, at.size(), progress, queued, at.size() / seconds, gap, last_iteration);
  return 0;
}

struct Victim {
  double latency = 0, optimize = 0;
  std::string error;
};

Victim AskVictim(v1::AlignSet::Stub& stub, uint32_t n, double dir, double deadline) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::microseconds(static_cast<int64_t>(deadline * 1e6)));
  v1::AlignedSetResponse resp;
  const auto t0 = Clock::now();
  grpc::Status s = stub.GetAlignedSet(&ctx, Request(n, {dir}), &resp);
  Victim v;
  v.latency = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!s.ok()) {
    v.error = std::to_string(s.error_code()) + " " + s.error_message();
  } else {
    v.optimize = resp.metadata().optimize_seconds();
    if (resp.metadata().from_cache()) v.error = "hit (not a new set)";
  }
  return v;
}

void Report(const char* phase, const std::vector<Victim>& vs) {
  std::vector<double> waits;
  for (size_t i = 0; i < vs.size(); ++i) {
    const Victim& v = vs[i];
    if (v.error.empty()) {
      waits.push_back(v.latency - v.optimize);
      std::printf("%s victim %zu latency_s %.3f own_optimization_s %.3f wait_s %.3f\n", phase, i, v.latency,
                  v.optimize, v.latency - v.optimize);
    } else {
      std::printf("%s victim %zu latency_s %.3f FAILED %s\n", phase, i, v.latency, v.error.c_str());
    }
  }
  std::sort(waits.begin(), waits.end());
  if (!waits.empty()) {
    std::printf("%s median_wait_s %.3f max_wait_s %.3f (%zu of %zu served)\n", phase, waits[waits.size() / 2],
                waits.back(), waits.size(), vs.size());
  } else {
    std::printf("%s none of %zu served\n", phase, vs.size());
  }
}

int Greedy(const std::map<std::string, std::string>& f) {
  const std::string address = Flag(f, "server", "127.0.0.1:50051");
  const int greedy = std::stoi(Flag(f, "greedy", "50"));
  const uint32_t greedy_n = static_cast<uint32_t>(std::stoul(Flag(f, "greedy-n", "32768")));
  const uint32_t precompute_n = static_cast<uint32_t>(std::stoul(Flag(f, "precompute-n", "32768")));
  const int victims = std::stoi(Flag(f, "victims", "5"));
  const uint32_t victim_n = static_cast<uint32_t>(std::stoul(Flag(f, "victim-n", "256")));
  const double deadline = std::stod(Flag(f, "deadline", "60"));

  auto greedy_stub = v1::AlignSet::NewStub(OwnChannel(address));
  auto victim_stub = v1::AlignSet::NewStub(OwnChannel(address));
  auto wait_for = [&](auto pred) {
    const auto t0 = Clock::now();
    while (!pred(Metrics(*greedy_stub)) && Clock::now() - t0 < std::chrono::seconds(30)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  };

  grpc::ClientContext pre_ctx;
  v1::PrecomputeRequest pre;
  pre.add_n(precompute_n);
  pre.set_space(v1::TWO_DIRECTIONS);
  auto pre_stream = greedy_stub->Precompute(&pre_ctx, pre);
  std::atomic<uint64_t> pre_messages{0};
  std::thread pre_reader([&] {
    v1::PrecomputeProgress p;
    while (pre_stream->Read(&p)) ++pre_messages;
  });
  wait_for([](const v1::MetricsResponse& m) { return m.running() >= 1; });
  std::this_thread::sleep_for(std::chrono::seconds(1));

  int dir = 1;
  std::vector<Victim> a;
  for (int i = 0; i < victims; ++i) a.push_back(AskVictim(*victim_stub, victim_n, dir++, deadline));
  Report("precompute_running", a);

  AsyncCalls held(greedy_stub.get());
  for (int i = 0; i < greedy; ++i) held.Start(Request(greedy_n + 16 * static_cast<uint32_t>(i), {30.0}));
  wait_for([&](const v1::MetricsResponse& m) { return m.queue_length() >= static_cast<uint32_t>(greedy) - 1; });
  std::this_thread::sleep_for(std::chrono::seconds(1));
  std::printf("greedy queue_length %u running %u precompute_messages %llu\n", Metrics(*greedy_stub).queue_length(),
              Metrics(*greedy_stub).running(), static_cast<unsigned long long>(pre_messages.load()));
  std::vector<Victim> b;
  for (int i = 0; i < victims; ++i) b.push_back(AskVictim(*victim_stub, victim_n, dir++, deadline));
  Report("greedy_queued", b);

  held.CancelAndDrain();
  pre_ctx.TryCancel();
  pre_reader.join();
  pre_stream->Finish();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: alignset_probe_client waiting|watch|greedy --flag value ...\n");
    return 2;
  }
  const std::string mode = argv[1];
  const auto flags = ParseFlags(argc - 2, argv + 2);
  if (mode == "waiting") return Waiting(flags);
  if (mode == "watch") return Watch(flags);
  if (mode == "greedy") return Greedy(flags);
  std::fprintf(stderr, "alignset_probe_client: unknown mode '%s'\n", mode.c_str());
  return 2;
}
