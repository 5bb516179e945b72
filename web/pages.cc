#include "web/pages.h"

#include <fstream>
#include <sstream>

namespace wavebake::web {

std::optional<std::string> Pages::Get(std::string_view name) const {
  for (const EmbeddedFile& f : EmbeddedPages()) {
    if (f.name != name) continue;
    if (dir_.empty()) return std::string(f.bytes);
    std::ifstream in(dir_ / std::string(f.name), std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  return std::nullopt;
}

const char* Pages::ContentType(std::string_view name) {
  if (name.ends_with(".html")) return "text/html; charset=utf-8";
  if (name.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (name.ends_with(".css")) return "text/css; charset=utf-8";
  if (name.ends_with(".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

}  // namespace wavebake::web
