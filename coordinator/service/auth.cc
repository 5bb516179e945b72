#include "coordinator/service/auth.h"

#include <string_view>

namespace wavebake {
namespace {

// Compares in time independent of where the strings differ.
bool ConstantTimeEquals(std::string_view a, std::string_view b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < a.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i] ^ (i < b.size() ? b[i] : 0));
  }
  return diff == 0;
}

}  // namespace

grpc::Status TokenAuth::Check(const grpc::ServerContext& context) const {
  if (!enabled()) return grpc::Status::OK;
  const auto& metadata = context.client_metadata();
  auto it = metadata.find("authorization");
  if (it == metadata.end()) {
    return {grpc::StatusCode::UNAUTHENTICATED, "authorization: missing bearer token"};
  }
  std::string_view value(it->second.data(), it->second.size());
  constexpr std::string_view kPrefix = "Bearer ";
  if (!value.starts_with(kPrefix) || !Matches(value.substr(kPrefix.size()))) {
    return {grpc::StatusCode::UNAUTHENTICATED, "authorization: wrong bearer token"};
  }
  return grpc::Status::OK;
}

bool TokenAuth::Matches(std::string_view token) const { return ConstantTimeEquals(token, token_); }

}  // namespace wavebake
