#pragma once
// SHA-256 for content addressing (DESIGN.md §4): the coordinator names
// uploaded scenes by it, and a worker checks that the bytes it fetched hash
// to the name it asked for before caching them.
#include <openssl/evp.h>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace wavebake {

// Incremental SHA-256 over bytes fed in pieces.
class Sha256 {
 public:
  Sha256();
  void Update(std::string_view bytes);
  // 64 lowercase hex digits. Ends the hash: call once.
  std::string HexDigest();

 private:
  struct Free {
    void operator()(EVP_MD_CTX* ctx) const { EVP_MD_CTX_free(ctx); }
  };
  std::unique_ptr<EVP_MD_CTX, Free> ctx_;
};

// SHA-256 of bytes as 64 lowercase hex digits.
std::string Sha256Hex(std::string_view bytes);

// SHA-256 of a file's contents; an error names the file.
absl::StatusOr<std::string> Sha256OfFile(const std::filesystem::path& path);

}  // namespace wavebake
