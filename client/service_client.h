#pragma once

// The client API moved to <alignset/client.h>, namespace alignset (the
// installed public header). This shim keeps code written against the old
// names (alignset::cli::ServiceClient, ...) building; new code includes
// <alignset/client.h> and says alignset::ServiceClient.
#include <alignset/client.h>

namespace alignset::cli {
using alignset::AlignedSet;
using alignset::BatchItem;
using alignset::CachedKey;
using alignset::CacheInfo;
using alignset::CallOptions;
using alignset::ConnectOptions;
using alignset::DecodePoints;
using alignset::DirectionReply;
using alignset::EstimatedDirection;
using alignset::kDefaultServerAddress;
using alignset::PrecomputeSpec;
using alignset::PrecomputeUpdate;
using alignset::ServiceClient;
using alignset::ServiceMetrics;
using alignset::SetInfo;
using alignset::SetRequest;
using alignset::WatchUpdate;
}  // namespace alignset::cli
