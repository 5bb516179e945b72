#pragma once
// The monitor's own files (web/static/: HTML, JS, CSS), built into the
// binary by CMake (cmake/embed_files.cmake writes them as byte arrays), or
// read from a directory that holds files of the same names.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace wavebake::web {

struct EmbeddedFile {
  std::string_view name;  // e.g. "monitor.js"
  std::string_view bytes;
};
// Generated at build time (web_pages.cc in the build tree).
std::span<const EmbeddedFile> EmbeddedPages();

class Pages {
 public:
  explicit Pages(std::filesystem::path dir = {}) : dir_(std::move(dir)) {}
  // A file of the built-in set by name; nullopt for any other name, so a
  // request never reaches another file of the directory.
  std::optional<std::string> Get(std::string_view name) const;
  static const char* ContentType(std::string_view name);

 private:
  std::filesystem::path dir_;
};

}  // namespace wavebake::web
