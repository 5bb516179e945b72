#include "coordinator/service/worker_paths.h"

#include <array>

#include "absl/strings/str_cat.h"
#include "proto/bake_request.h"

namespace wavebake {
namespace {

// What ends a path in a message: "cannot write /a/b: No space", "'/a/b'",
// "(/a/b)". A path with one of these in a name is cut there, which only
// leaves more of it hidden.
bool EndsPath(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\'' || c == '"' || c == '`' || c == '(' ||
         c == ')' || c == '[' || c == ']' || c == ',' || c == ';' || c == '=' || c == '<' ||
         c == '>' || c == ':';
}

// `token` with the part before the job's store replaced, or nullopt-like ""
// when it does not pass through the store.
std::string ThroughStore(absl::string_view token, const std::array<std::string, 2>& stores) {
  for (const std::string& store : stores) {
    if (store.empty()) continue;
    for (size_t at = token.find(store); at != token.npos; at = token.find(store, at + 1)) {
      const size_t end = at + store.size();
      const bool whole =
          at > 0 && token[at - 1] == '/' && (end == token.size() || token[end] == '/');
      if (whole) return absl::StrCat("<store root>/", token.substr(at));
    }
  }
  return {};
}

}  // namespace

std::string HideWorkerPaths(absl::string_view reason, const std::string& store_path) {
  const std::array<std::string, 2> stores = {
      store_path.empty() ? std::string() : PartialStorePath(store_path), store_path};
  std::string out;
  out.reserve(reason.size());
  size_t i = 0;
  while (i < reason.size()) {
    if (EndsPath(reason[i])) {
      out.push_back(reason[i++]);
      continue;
    }
    size_t end = i;
    while (end < reason.size() && !EndsPath(reason[end])) ++end;
    const absl::string_view token = reason.substr(i, end - i);
    if (std::string hidden = ThroughStore(token, stores); !hidden.empty()) {
      out += hidden;
    } else if (token.size() > 1 && token.front() == '/' && token.find('/', 1) != token.npos) {
      absl::StrAppend(&out, "<worker>", token.substr(token.rfind('/')));
    } else {
      out.append(token.data(), token.size());
    }
    i = end;
  }
  return out;
}

}  // namespace wavebake
