#pragma once
// Every regular file under a directory by relative path, with its bytes: the
// stores of two bakes are bit-identical (DESIGN.md §1 "Determinism") when
// these maps are equal.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace wavebake::test_support {

inline std::map<std::string, std::string> ReadTree(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    files[std::filesystem::relative(e.path(), dir).string()] = bytes.str();
  }
  return files;
}

}  // namespace wavebake::test_support
