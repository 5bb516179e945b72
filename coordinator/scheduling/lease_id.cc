#include "coordinator/scheduling/lease_id.h"

#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"

namespace wavebake {

std::string FormatLeaseId(const LeaseKey& key) {
  return absl::StrCat(key.job_id, ".", key.task, ".", key.attempt);
}

std::optional<LeaseKey> ParseLeaseId(absl::string_view id) {
  const std::vector<absl::string_view> parts = absl::StrSplit(id, '.');
  LeaseKey key;
  if (parts.size() != 3 || !absl::SimpleAtoi(parts[0], &key.job_id) ||
      !absl::SimpleAtoi(parts[1], &key.task) || !absl::SimpleAtoi(parts[2], &key.attempt) ||
      key.job_id <= 0 || key.task < 0 || key.attempt <= 0) {
    return std::nullopt;
  }
  return key;
}

std::optional<int64_t> ParseId(absl::string_view id) {
  int64_t v = 0;
  if (id.empty() || id.size() > 19 || id.find_first_not_of("0123456789") != id.npos ||
      !absl::SimpleAtoi(id, &v) || v <= 0) {
    return std::nullopt;
  }
  return v;
}

}  // namespace wavebake
