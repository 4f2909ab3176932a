#include "server/reflection_service.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>

#include <set>

#include "server/log_text.h"

namespace alignset::server {
namespace {

namespace rpb = grpc::reflection::v1alpha;
using google::protobuf::DescriptorPool;
using google::protobuf::FileDescriptor;

// The file and everything it imports, each once, dependencies first.
void AddFileAndImports(const FileDescriptor* file, std::set<std::string>* seen,
                       rpb::FileDescriptorResponse* out) {
  if (!seen->insert(file->name()).second) return;
  for (int i = 0; i < file->dependency_count(); ++i) AddFileAndImports(file->dependency(i), seen, out);
  google::protobuf::FileDescriptorProto proto;
  file->CopyTo(&proto);
  proto.SerializeToString(out->add_file_descriptor_proto());
}

void SetError(rpb::ServerReflectionResponse* resp, grpc::StatusCode code, const std::string& message) {
  resp->mutable_error_response()->set_error_code(static_cast<int32_t>(code));
  resp->mutable_error_response()->set_error_message(message);
}

}  // namespace

ReflectionService::ReflectionService(std::vector<std::string> services,
                                     std::function<grpc::Status(grpc::ServerContext*)> authorize)
    : services_(std::move(services)), authorize_(std::move(authorize)) {}

rpb::ServerReflectionResponse ReflectionService::Answer(const rpb::ServerReflectionRequest& req) const {
  rpb::ServerReflectionResponse resp;
  resp.set_valid_host(req.host());
  *resp.mutable_original_request() = req;
  const DescriptorPool* pool = DescriptorPool::generated_pool();
  std::set<std::string> seen;
  switch (req.message_request_case()) {
    case rpb::ServerReflectionRequest::kListServices:
      for (const std::string& s : services_) resp.mutable_list_services_response()->add_service()->set_name(s);
      break;
    case rpb::ServerReflectionRequest::kFileByFilename: {
      const FileDescriptor* f = pool->FindFileByName(req.file_by_filename());
      if (f == nullptr) {
        SetError(&resp, grpc::StatusCode::NOT_FOUND, "no file " + Quoted(req.file_by_filename()));
      } else {
        AddFileAndImports(f, &seen, resp.mutable_file_descriptor_response());
      }
      break;
    }
    case rpb::ServerReflectionRequest::kFileContainingSymbol: {
      const FileDescriptor* f = pool->FindFileContainingSymbol(req.file_containing_symbol());
      if (f == nullptr) {
        SetError(&resp, grpc::StatusCode::NOT_FOUND, "no symbol " + Quoted(req.file_containing_symbol()));
      } else {
        AddFileAndImports(f, &seen, resp.mutable_file_descriptor_response());
      }
      break;
    }
    case rpb::ServerReflectionRequest::kFileContainingExtension: {
      const auto& e = req.file_containing_extension();
      const auto* type = pool->FindMessageTypeByName(e.containing_type());
      const auto* ext = type ? pool->FindExtensionByNumber(type, e.extension_number()) : nullptr;
      if (ext == nullptr) {
        SetError(&resp, grpc::StatusCode::NOT_FOUND, "no such extension");
      } else {
        AddFileAndImports(ext->file(), &seen, resp.mutable_file_descriptor_response());
      }
      break;
    }
    case rpb::ServerReflectionRequest::kAllExtensionNumbersOfType: {
      const auto* type = pool->FindMessageTypeByName(req.all_extension_numbers_of_type());
      if (type == nullptr) {
        SetError(&resp, grpc::StatusCode::NOT_FOUND, "no type " + Quoted(req.all_extension_numbers_of_type()));
        break;
      }
      std::vector<const google::protobuf::FieldDescriptor*> extensions;
      pool->FindAllExtensions(type, &extensions);
      auto* out = resp.mutable_all_extension_numbers_response();
      out->set_base_type_name(type->full_name());
      for (const auto* x : extensions) out->add_extension_number(x->number());
      break;
    }
    default:
      SetError(&resp, grpc::StatusCode::INVALID_ARGUMENT, "empty reflection request");
  }
  return resp;
}

grpc::Status ReflectionService::ServerReflectionInfo(
    grpc::ServerContext* ctx,
    grpc::ServerReaderWriter<rpb::ServerReflectionResponse, rpb::ServerReflectionRequest>* stream) {
  if (grpc::Status a = authorize_(ctx); !a.ok()) return a;
  rpb::ServerReflectionRequest req;
  while (stream->Read(&req)) {
    if (!stream->Write(Answer(req))) break;
  }
  return grpc::Status::OK;
}

}  // namespace alignset::server
