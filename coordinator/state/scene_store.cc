#include "coordinator/state/scene_store.h"

#include <atomic>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace wavebake {
SceneStore::SceneStore(std::filesystem::path data_dir, JobStore* db, const Clock* clock,
                       int64_t max_bytes)
    : dir_(data_dir / "scenes"), db_(db), clock_(clock), max_bytes_(max_bytes) {}

std::filesystem::path SceneStore::BlobPath(const std::filesystem::path& data_dir,
                                           absl::string_view sha256) {
  return data_dir / "scenes" / std::string(sha256);
}

std::filesystem::path SceneStore::BlobPath(absl::string_view sha256) const {
  return dir_ / std::string(sha256);
}

absl::StatusOr<std::unique_ptr<SceneUpload>> SceneStore::BeginUpload(absl::string_view file_name) {
  const std::string name = std::filesystem::path(std::string(file_name)).filename().string();
  if (name.empty() || name == "." || name == ".." || name.size() > 255) {
    return absl::InvalidArgumentError(absl::StrCat(
        "file_name: \"", file_name, "\" is not a file name (the first chunk names the file)"));
  }
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec)
    return absl::InternalError(absl::StrCat("scenes dir ", dir_.string(), ": ", ec.message()));
  static std::atomic<uint64_t> counter{0};
  const std::filesystem::path temp =
      dir_ / absl::StrCat(".upload-", clock_->NowMs(), "-", counter++, ".tmp");
  auto upload = std::make_unique<SceneUpload>(this, name, temp);
  return upload;
}

absl::StatusOr<std::optional<SceneRecord>> SceneStore::Find(const std::string& sha256) const {
  absl::StatusOr<std::optional<SceneRecord>> rec = db_->GetScene(sha256);
  if (!rec.ok() || !rec->has_value()) return rec;
  // A record without its file (deleted by hand) is no scene.
  if (!std::filesystem::exists(BlobPath(sha256))) return std::nullopt;
  return rec;
}

SceneUpload::SceneUpload(SceneStore* store, std::string file_name, std::filesystem::path temp_path)
    : store_(store),
      file_name_(std::move(file_name)),
      temp_path_(std::move(temp_path)),
      out_(temp_path_, std::ios::binary | std::ios::trunc) {}

SceneUpload::~SceneUpload() {
  if (finished_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(temp_path_, ec);
}

absl::Status SceneUpload::Append(absl::string_view data) {
  if (!out_) return absl::InternalError(absl::StrCat("cannot write ", temp_path_.string()));
  size_ += static_cast<int64_t>(data.size());
  if (size_ > store_->max_bytes_) {
    return absl::InvalidArgumentError(absl::StrCat(
        "data: upload exceeds the coordinator's limit of ", store_->max_bytes_, " bytes"));
  }
  out_.write(data.data(), static_cast<std::streamsize>(data.size()));
  sha_.Update(std::string_view(data.data(), data.size()));
  if (!out_) return absl::InternalError(absl::StrCat("cannot write ", temp_path_.string()));
  return absl::OkStatus();
}

absl::StatusOr<SceneRecord> SceneUpload::Finish(absl::string_view expected_sha256) {
  out_.close();
  if (!out_) return absl::InternalError(absl::StrCat("cannot write ", temp_path_.string()));
  if (size_ == 0) return absl::InvalidArgumentError("data: the scene file is empty");
  SceneRecord rec{.sha256 = sha_.HexDigest(),
                  .size = size_,
                  .file_name = file_name_,
                  .created_ms = store_->clock_->NowMs()};
  if (!expected_sha256.empty() && expected_sha256 != rec.sha256) {
    return absl::InvalidArgumentError(
        absl::StrCat("sha256: the upload hashes to ", rec.sha256, ", not ", expected_sha256));
  }
  const std::filesystem::path final_path = store_->BlobPath(rec.sha256);
  std::error_code ec;
  if (std::filesystem::exists(final_path, ec)) {
    std::filesystem::remove(temp_path_, ec);  // same bytes already stored: keep one copy
  } else {
    std::filesystem::rename(temp_path_, final_path, ec);  // atomic: readers see all or nothing
    if (ec)
      return absl::InternalError(
          absl::StrCat("rename to ", final_path.string(), ": ", ec.message()));
  }
  finished_ = true;
  if (absl::Status s = store_->db_->PutScene(rec); !s.ok()) return s;
  return rec;
}

}  // namespace wavebake
