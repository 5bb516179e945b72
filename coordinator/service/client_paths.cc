#include "coordinator/service/client_paths.h"

#include <algorithm>
#include <system_error>

#include "absl/strings/str_replace.h"

namespace wavebake {

void ClientPaths::Hide(const std::filesystem::path& dir, const std::string& label) {
  std::error_code ec;
  std::filesystem::path normal = std::filesystem::absolute(dir, ec).lexically_normal();
  if (!normal.has_filename()) normal = normal.parent_path();
  // Absolute spellings only: a relative one ("data") would match inside words.
  for (std::string form :
       {dir.string(), normal.string(), std::filesystem::weakly_canonical(dir, ec).string()}) {
    while (form.size() > 1 && form.back() == '/') form.pop_back();
    if (!form.starts_with('/') || form == "/") continue;
    hidden_.emplace_back(form, label);
  }
  // The longest first, so that a store root inside the data dir keeps its label.
  std::sort(hidden_.begin(), hidden_.end(),
            [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
}

std::string ClientPaths::operator()(std::string message) const {
  // One pass: a label is never matched again.
  std::vector<std::pair<absl::string_view, absl::string_view>> replacements(hidden_.begin(),
                                                                            hidden_.end());
  absl::StrReplaceAll(replacements, &message);
  return message;
}

}  // namespace wavebake
