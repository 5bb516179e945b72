#include "web/views/job_gpu.h"

#include "absl/strings/str_cat.h"
#include "runtime/relight/store_relight.h"
#include "storage/store/store_reader.h"
#include "web/views/store_view.h"

namespace wavebake::web {

absl::StatusOr<std::shared_ptr<const ServedColumns>> JobGpu::Open(
    const std::filesystem::path& store) {
  const std::string key = store.lexically_normal().string();
  {
    std::lock_guard lock(mu_);
    for (auto it = open_.begin(); it != open_.end(); ++it) {
      if (it->first != key) continue;
      open_.splice(open_.begin(), open_, it);
      return open_.front().second;
    }
  }
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (absl::Status s = RequireCubeDomain(*info); !s.ok()) return s;
  if (info->params.transport != Transport::kDiffuse)
    return absl::FailedPreconditionError(
        "store: transport is visibility; the GPU path relights diffuse stores");
  if (PictureKindOf(info->params.layout) == PictureKind::kVertexColours)
    return absl::FailedPreconditionError(
        absl::StrCat("store: layout ", info->params.layout,
                     " is drawn as the mesh's vertex colours by the server"));
  absl::StatusOr<SampleSet> samples = ReadSamples(store);
  if (!samples.ok()) return samples.status();
  absl::StatusOr<CompressedColumns> columns = ReadTransport(store);
  if (!columns.ok()) return columns.status();
  absl::StatusOr<ServedColumns> served = ServeColumns(*columns, *samples, false);
  if (!served.ok()) return served.status();
  auto shared = std::make_shared<const ServedColumns>(*std::move(served));
  std::lock_guard lock(mu_);
  open_.emplace_front(key, shared);
  while (open_.size() > max_open_) open_.pop_back();
  return shared;
}

}  // namespace wavebake::web
