#include "core/bake/bake_param_words.h"

#include "core/bake/bake_params_io.h"
#include "core/layouts/layout.h"

namespace wavebake {

absl::StatusOr<BakeParams> ParseBakeParamWords(BakeParams p, const BakeParamWords& w) {
  for (const auto& [name, word] : w.words) {
    bool known = false;
    absl::Status s = absl::OkStatus();
    params::ForEach([&, &name = name, &word = word](const auto& row) {
      if (row.info.name != name || !params::InWords(row)) return;
      known = true;
      s = params::ParseInto(row, word, p);
    });
    if (!known)
      return absl::InvalidArgumentError(absl::StrCat(name, ": not a bake parameter in words"));
    if (!s.ok()) return s;
  }
  if (w.allow_uv_overlap) {
    absl::StatusOr<std::string> layout = WithUvOverlapAllowed(p.layout);
    if (!layout.ok()) return layout.status();
    p.layout = *layout;
  }
  if (absl::Status s = ValidateBakeParams(p); !s.ok()) return s;
  return p;
}

}  // namespace wavebake
