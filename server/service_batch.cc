// GetAlignedSets: many aligned sets in one call, each served as GetAlignedSet
// serves one (validate, canonicalize, acquire, wait, align) and each with its
// own status. Every item's ticket is taken before the first wait, so the
// missing sets are optimized in parallel on the worker pool and the call takes
// about as long as its slowest item.
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>

#include "server/construction.h"
#include "server/service.h"
#include "server/validation.h"

namespace alignset::server {
namespace {

struct BatchItemState {
  v1::AlignedSetRequest request;
  std::optional<Canonicalization> canon;
  storage::SetKey key;
  std::unique_ptr<Ticket> ticket;
  Status status;  // the item's failure, before or after its wait
};

void SetItemStatus(const Status& s, v1::AlignedSetsItem* out) {
  const grpc::Status g = ToGrpc(s);
  out->set_code(static_cast<int32_t>(g.error_code()));
  out->set_message(g.error_message());
}

}  // namespace

grpc::Status AlignSetService::GetAlignedSets(grpc::ServerContext* ctx,
                                             const v1::AlignedSetsRequest* req,
                                             v1::AlignedSetsResponse* resp) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  // A batch holds this thread while it waits: their number is capped.
  struct BatchSlot {
    std::atomic<int>* count;
    ~BatchSlot() { count->fetch_sub(1); }
  } slot{&batch_calls_};
  if (batch_calls_.fetch_add(1) >= config_.max_batch_calls) {
    return grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                        std::to_string(config_.max_batch_calls) +
                            " GetAlignedSets batches are running (--max-batch-calls); retry later");
  }

  // The items: explicit, or every key of a space for one N.
  std::vector<BatchItemState> items;
  const bool has_space = req->space() != v1::KEY_SPACE_UNSPECIFIED;
  if (has_space == (req->items_size() > 0)) {
    return Invalid(Status::InvalidArgument("give either items or a space (with space_n), not both "
                                           "and not neither"),
                   "GetAlignedSets");
  }
  uint64_t total_points = 0;
  if (has_space) {
    if (req->space() != v1::ONE_DIRECTION) {
      return Invalid(Status::InvalidArgument(
                         "only space = ONE_DIRECTION (46 sets) fits one call; the two-direction "
                         "space has 4141 keys, above the maximum of " +
                         std::to_string(kMaxBatchItems) + " items: ask for them as items"),
                     "GetAlignedSets");
    }
    if (Status s = ValidatePointCount(req->space_n(), config_.max_n); !s.ok()) {
      return Invalid(s, "GetAlignedSets");
    }
    // Checked once for the call rather than refused 46 times, item by item.
    if (auto c = ParseConstruction(req->space_construction()); !c.ok()) {
      return Invalid(c.status(), "GetAlignedSets");
    } else if (Status s = (*c)->ValidateSize(req->space_n()); !s.ok()) {
      return Invalid(s, "GetAlignedSets");
    }
    for (size_t i = 0; i < CanonicalKeyCount(1); ++i) {
      BatchItemState item;
      item.request.set_n(req->space_n());
      item.request.add_directions_deg(CanonicalKeyAt(1, i).phi1);
      item.request.set_realization(req->space_realization());
      item.request.set_construction(req->space_construction());
      item.request.set_steps_per_degree(1);  // the 46 whole-degree keys
      items.push_back(std::move(item));
    }
  } else {
    if (Status s = ValidateBatchSize(static_cast<size_t>(req->items_size()), 0); !s.ok()) {
      return Invalid(s, "GetAlignedSets");
    }
    for (const v1::AlignedSetRequest& r : req->items()) {
      BatchItemState item;
      item.request = r;
      items.push_back(std::move(item));
    }
  }
  for (const BatchItemState& item : items) total_points += item.request.n();
  if (Status s = ValidateBatchSize(items.size(), total_points); !s.ok()) {
    return Invalid(s, "GetAlignedSets");
  }

  // Every ticket first (optimizations start in parallel), then the waits.
  for (BatchItemState& item : items) {
    auto canon = Canonicalize(item.request);
    if (!canon.ok()) {
      metrics_->requests_invalid.fetch_add(1, std::memory_order_relaxed);
      item.status = canon.status();
      continue;
    }
    auto key = KeyOf(item.request, *canon);
    if (!key.ok()) {
      metrics_->requests_invalid.fetch_add(1, std::memory_order_relaxed);
      item.status = key.status();
      continue;
    }
    item.canon = *canon;
    item.key = std::move(key).value();
    auto ticket = scheduler_->Acquire(item.key, Priority::kInteractive, ctx->peer());
    if (!ticket.ok()) {
      item.status = ticket.status();
      continue;
    }
    item.ticket = std::move(ticket).value();
  }
  int served = 0;
  for (BatchItemState& item : items) {
    v1::AlignedSetsItem* out = resp->add_items();
    if (item.ticket) {
      // A client that leaves ends the whole call; the tickets are released
      // with `items`, so optimizations nobody else wants are dropped.
      while (!item.ticket->Wait(std::chrono::milliseconds(50))) {
        if (ctx->IsCancelled()) {
          spdlog::info("GetAlignedSets: client stopped waiting after {} of {} items", served,
                       items.size());
          return ctx->deadline() <= std::chrono::system_clock::now()
                     ? grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                                    "deadline exceeded while waiting for the optimizations")
                     : grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by the client");
        }
      }
      auto entry = item.ticket->Result();
      if (entry.ok()) {
        FillSet(*item.canon, item.key, **entry, item.ticket->from_cache(), out->mutable_set());
        ++served;
        continue;
      }
      item.status = entry.status();
    }
    SetItemStatus(item.status, out);
  }
  spdlog::debug("GetAlignedSets: {} of {} items served", served, items.size());
  return grpc::Status::OK;
}

}  // namespace alignset::server
