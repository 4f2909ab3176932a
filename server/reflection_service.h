#pragma once

#include <functional>
#include <string>
#include <vector>

#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"

namespace alignset::server {

// gRPC server reflection (what grpcurl and grpc_cli ask), answered from the
// descriptors compiled into this binary. Written here rather than taken from
// gRPC's reflection plugin because the plugin cannot be made to check a
// bearer token: with --token-file, reflection answers only authorized
// callers, like the service it describes (the health service stays open for
// probes).
class ReflectionService final : public grpc::reflection::v1alpha::ServerReflection::Service {
 public:
  // `services`: the full names listed by list_services. `authorize` decides
  // each stream from its metadata (OK: answer it).
  ReflectionService(std::vector<std::string> services,
                    std::function<grpc::Status(grpc::ServerContext*)> authorize);

  grpc::Status ServerReflectionInfo(
      grpc::ServerContext* ctx,
      grpc::ServerReaderWriter<grpc::reflection::v1alpha::ServerReflectionResponse,
                               grpc::reflection::v1alpha::ServerReflectionRequest>* stream) override;

 private:
  grpc::reflection::v1alpha::ServerReflectionResponse Answer(
      const grpc::reflection::v1alpha::ServerReflectionRequest& req) const;

  const std::vector<std::string> services_;
  const std::function<grpc::Status(grpc::ServerContext*)> authorize_;
};

}  // namespace alignset::server
