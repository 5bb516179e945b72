#pragma once
// A fresh directory for one test, under the build tree (so a failed run's
// leftovers are where the build is, not in /tmp), removed with everything in
// it. Header-only: every test module includes it from the source root.
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace wavebake::test_support {

class ScratchDir {
 public:
  // prefix: names the directory after its user, for whoever finds one left.
  explicit ScratchDir(const std::string& prefix = "test") {
    const std::filesystem::path root = std::filesystem::path(WB_BINARY_DIR) / "test_tmp";
    std::filesystem::create_directories(root);
    std::string tmpl = (root / (prefix + "_XXXXXX")).string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + tmpl);
    path_ = tmpl;
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace wavebake::test_support
