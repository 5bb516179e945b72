#include "worker/columns/shard_plan.h"

#include <algorithm>
#include <cstring>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"

namespace wavebake {
namespace {

// "WBP1", groups and columns (int32), max_code (int32), then the group
// offsets (int64) and the steps (float32), native byte order (written and
// read by the same build's workers within one job).
constexpr char kPlanMagic[4] = {'W', 'B', 'P', '1'};
constexpr size_t kPlanHeader = sizeof kPlanMagic + 3 * sizeof(int32_t);

size_t PlanFileBytes(size_t groups, size_t columns) {
  return kPlanHeader + (groups + 1) * sizeof(int64_t) + columns * sizeof(float);
}

}  // namespace

std::filesystem::path ShardPlanPath(const std::filesystem::path& store) {
  return store::Path(store, store::kStagingFinalize) / "plan.wbp";
}

absl::Status WriteShardPlan(const std::filesystem::path& store, const ShardPlan& plan) {
  const int32_t header[3] = {static_cast<int32_t>(plan.group_offsets.size() - 1),
                             static_cast<int32_t>(plan.steps.size()), plan.max_code};
  std::vector<std::byte> out(PlanFileBytes(plan.group_offsets.size() - 1, plan.steps.size()));
  std::byte* p = out.data();
  for (auto [src, n] : {std::pair<const void*, size_t>{kPlanMagic, sizeof kPlanMagic},
                        {header, sizeof header},
                        {plan.group_offsets.data(), plan.group_offsets.size() * sizeof(int64_t)},
                        {plan.steps.data(), plan.steps.size() * sizeof(float)}}) {
    std::memcpy(p, src, n);
    p += n;
  }
  const std::filesystem::path path = ShardPlanPath(store);
  if (absl::Status s = CreateDirectories(path.parent_path()); !s.ok()) return s;
  return AtomicWriteFile(path, out);
}

absl::StatusOr<ShardPlan> ReadShardPlan(const std::filesystem::path& store, const JobPlan& job) {
  const std::filesystem::path path = ShardPlanPath(store);
  absl::StatusOr<std::vector<std::byte>> in = ReadFile(path);
  if (!in.ok()) return in.status();
  int32_t header[3] = {};
  const bool sized = in->size() == PlanFileBytes(job.groups, job.columns);
  if (sized) std::memcpy(header, in->data() + sizeof kPlanMagic, sizeof header);
  if (!sized || std::memcmp(in->data(), kPlanMagic, sizeof kPlanMagic) != 0 ||
      header[0] != job.groups || header[1] != job.columns) {
    return absl::DataLossError(absl::StrCat(path.string(), ": not a FINALIZE plan of ", job.groups,
                                            " groups and ", job.columns, " columns"));
  }
  ShardPlan plan;
  plan.max_code = header[2];
  plan.group_offsets.resize(size_t(job.groups) + 1);
  plan.steps.resize(size_t(job.columns));
  const std::byte* p = in->data() + kPlanHeader;
  std::memcpy(plan.group_offsets.data(), p, plan.group_offsets.size() * sizeof(int64_t));
  p += plan.group_offsets.size() * sizeof(int64_t);
  std::memcpy(plan.steps.data(), p, plan.steps.size() * sizeof(float));
  if (plan.group_offsets.front() != 0 ||
      !std::is_sorted(plan.group_offsets.begin(), plan.group_offsets.end()))
    return absl::DataLossError(absl::StrCat(path.string(), ": group offsets out of order"));
  return plan;
}

absl::Status RemoveShardPlan(const std::filesystem::path& store) {
  std::error_code ec;
  std::filesystem::remove(ShardPlanPath(store), ec);
  if (ec)
    return absl::InternalError(absl::StrCat(ShardPlanPath(store).string(), ": ", ec.message()));
  return absl::OkStatus();
}

}  // namespace wavebake
