#include "web/views/probe_catalogue.h"

#include <algorithm>
#include <cctype>

#include "absl/strings/str_cat.h"

namespace wavebake::web {
namespace {

bool IsProbeFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".hdr" || ext == ".exr";
}

}  // namespace

ProbeCatalogue::ProbeCatalogue() {
  for (const char* b : {"builtin:sky", "builtin:constant"}) {
    order_.push_back(b);
    specs_[b] = b;
  }
}

absl::StatusOr<ProbeCatalogue> ProbeCatalogue::Scan(const std::filesystem::path& dir) {
  ProbeCatalogue c;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return absl::InvalidArgumentError(
        absl::StrCat("--probes: ", dir.string(), " is not a directory"));
  }
  std::vector<std::string> files;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec) || !IsProbeFile(it->path())) continue;
    const std::string name = std::filesystem::relative(it->path(), dir).generic_string();
    files.push_back(name);
    c.specs_[name] = std::filesystem::absolute(it->path()).string();
  }
  if (ec)
    return absl::InvalidArgumentError(absl::StrCat("--probes: ", dir.string(), ": ", ec.message()));
  std::sort(files.begin(), files.end());
  c.order_.insert(c.order_.end(), files.begin(), files.end());
  return c;
}

std::vector<std::string> ProbeCatalogue::names() const { return order_; }

absl::StatusOr<std::string> ProbeCatalogue::Spec(const std::string& name) const {
  auto it = specs_.find(name);
  if (it == specs_.end()) {
    return absl::NotFoundError(
        absl::StrCat("probe: \"", name, "\" is not one of the server's probes"));
  }
  return it->second;
}

}  // namespace wavebake::web
