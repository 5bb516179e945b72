#pragma once
// A lease id names one grant of one task: "<job>.<task index>.<attempt>".
// Carrying the attempt lets the coordinator tell a stale lease (an earlier
// grant of a task that expired and was handed out again) from the current one
// without a table of every lease ever granted.
#include <cstdint>
#include <optional>
#include <string>

#include "absl/strings/string_view.h"

namespace wavebake {

struct LeaseKey {
  int64_t job_id = 0;
  int task = 0;
  int attempt = 0;
  bool operator==(const LeaseKey&) const = default;
};

std::string FormatLeaseId(const LeaseKey& key);
std::optional<LeaseKey> ParseLeaseId(absl::string_view id);

// Decimal ids of jobs and workers ("42"); nullopt unless a positive integer.
std::optional<int64_t> ParseId(absl::string_view id);

}  // namespace wavebake
