#include "server/fill_client.h"

#include <condition_variable>
#include <mutex>

#include <grpcpp/grpcpp.h>

#include <cstring>
#include <memory>

#include "alignset/v1/alignset.grpc.pb.h"
#include "core/align/canonical.h"
#include "server/construction.h"
#include "server/set_lru.h"

namespace alignset::server {
namespace {

Status FromGrpc(const grpc::Status& s, const std::string& what) {
  const std::string m = what + ": " + s.error_message();
  switch (s.error_code()) {
    case grpc::StatusCode::NOT_FOUND: return Status::NotFound(m);
    case grpc::StatusCode::INVALID_ARGUMENT: return Status::InvalidArgument(m);
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return Status::ResourceExhausted(m);
    case grpc::StatusCode::DEADLINE_EXCEEDED: return Status::DeadlineExceeded(m);
    case grpc::StatusCode::CANCELLED: return Status::Cancelled(m);
    case grpc::StatusCode::DATA_LOSS: return Status::DataLoss(m);
    case grpc::StatusCode::FAILED_PRECONDITION: return Status::FailedPrecondition(m);
    default: return Status::Unavailable(m);  // the writer is down, refused us, or broke
  }
}

}  // namespace

FillFunction MakeWriterFill(const std::string& address, const std::string& token, double timeout_seconds,
                            const std::string& tls_ca_pem, const std::string& tls_name) {
  std::shared_ptr<grpc::ChannelCredentials> creds = grpc::InsecureChannelCredentials();
  grpc::ChannelArguments args;
  if (!tls_ca_pem.empty()) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = tls_ca_pem;
    creds = grpc::SslCredentials(ssl);
    if (!tls_name.empty()) args.SetSslTargetNameOverride(tls_name);
  }
  auto stub = std::shared_ptr<v1::AlignSet::Stub>(
      v1::AlignSet::NewStub(grpc::CreateCustomChannel(address, creds, args)));
  return [stub, address, token, timeout_seconds](const storage::SetKey& key,
                                                 const FillCancelled& cancelled) -> StatusOr<storage::SetRecord> {
    const std::string name = KeyString(key);
    v1::AlignedSetRequest req;
    req.set_n(key.n);
    req.add_directions_deg(Phi1Degrees(key.dirs));
    if (key.dirs.count == 2) req.add_directions_deg(Phi2Degrees(key.dirs));
    req.set_steps_per_degree(key.dirs.count == 1 && key.dirs.phi1_quarter != 0 ? 4 : 1);
    req.set_realization(key.realization);
    // A lattice or net key asks the writer for its construction; any other
    // profile is the optimized construction (checked against the answer
    // below).
    if (const Construction& c = ConstructionOfProfile(key.profile); !c.optimized()) {
      req.set_construction(std::string(c.name));
    }
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() +
                     std::chrono::milliseconds(static_cast<int64_t>(timeout_seconds * 1000)));
    if (!token.empty()) ctx.AddMetadata("authorization", "Bearer " + token);
    v1::AlignedSetResponse resp;
    // Asynchronous, so that the caller's leaving can cancel the call.
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
    grpc::Status s;
    stub->async()->GetAlignedSet(&ctx, &req, &resp, [&](grpc::Status status) {
      std::lock_guard<std::mutex> lock(mu);
      s = std::move(status);
      done = true;
      cv.notify_all();
    });
    bool asked_to_cancel = false;
    {
      std::unique_lock<std::mutex> lock(mu);
      while (!cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
        if (!asked_to_cancel && cancelled && cancelled()) {
          asked_to_cancel = true;
          ctx.TryCancel();  // the callback still runs, with CANCELLED
        }
      }
    }
    if (asked_to_cancel && !s.ok()) {
      return Status::Cancelled("the fill of " + name + " from " + address + " was cancelled: every caller left");
    }
    if (!s.ok()) return FromGrpc(s, "the writer " + address + " for " + name);
    const v1::SetMetadata& md = resp.metadata();
    const v1::CanonicalKey& k = md.key();
    if (k.profile() != key.profile) {
      return Status::FailedPrecondition("the writer " + address + " serves profile " + k.profile() + ", this replica " +
                                        key.profile + " (other optimization settings): not used for " + name);
    }
    if (k.n() != key.n || k.text() != name || md.swapped() || md.inverted() || md.inverted_y()) {
      return Status::Internal("the writer " + address + " answered " + k.text() + " for " + name);
    }
    const std::string& bytes = resp.points();
    if (resp.n() != key.n || bytes.size() != size_t{16} * key.n) {
      return Status::Internal("the writer " + address + " sent " + std::to_string(bytes.size()) +
                              " bytes of points for " + name);
    }
    storage::SetRecord r;
    r.key = key;
    r.points.resize(key.n);
    static_assert(sizeof(double) == 8);
    for (uint32_t i = 0; i < key.n; ++i) {  // little-endian float64 pairs, as on this host
      std::memcpy(&r.points[i].x, bytes.data() + 16 * i, 8);
      std::memcpy(&r.points[i].y, bytes.data() + 16 * i + 8, 8);
    }
    r.loss.total = md.loss().total();
    r.loss.spectrum = md.loss().spectrum();
    r.loss.sw = md.loss().sliced_wasserstein();
    r.iterations = md.iterations();
    r.optimize_seconds = md.optimize_seconds();
    r.engine = md.engine();
    return r;
  };
}

}  // namespace alignset::server
