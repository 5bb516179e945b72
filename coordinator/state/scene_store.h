#pragma once
// Uploaded scenes, content-addressed (DESIGN.md §4): the bytes live once in
// <data dir>/scenes/<sha256>, whatever name or how often they were uploaded;
// the `scenes` table records size and first file name. Workers fetch them by
// hash (FetchScene) and cache them.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "coordinator/scheduling/clock.h"
#include "coordinator/state/job_store.h"
#include "storage/files/sha256.h"

namespace wavebake {

class SceneStore;

// One upload in progress: bytes go to a temporary file while they are
// hashed; Finish renames it into place. Dropped unfinished, it removes the
// temporary file (§4: nothing half-written is left behind).
class SceneUpload {
 public:
  SceneUpload(SceneStore* store, std::string file_name, std::filesystem::path temp_path);
  SceneUpload(const SceneUpload&) = delete;
  SceneUpload& operator=(const SceneUpload&) = delete;
  ~SceneUpload();

  // INVALID_ARGUMENT "data: ..." once the upload passes the size limit.
  absl::Status Append(absl::string_view data);
  // expected_sha256: empty, or the hash the client computed (checked).
  absl::StatusOr<SceneRecord> Finish(absl::string_view expected_sha256);

 private:
  SceneStore* store_;
  std::string file_name_;
  std::filesystem::path temp_path_;
  std::ofstream out_;
  Sha256 sha_;
  int64_t size_ = 0;
  bool finished_ = false;
};

class SceneStore {
 public:
  SceneStore(std::filesystem::path data_dir, JobStore* db, const Clock* clock, int64_t max_bytes);

  // Where the bytes of a scene live: <data dir>/scenes/<sha256>. The planner
  // loads uploaded scenes from here.
  static std::filesystem::path BlobPath(const std::filesystem::path& data_dir,
                                        absl::string_view sha256);
  std::filesystem::path BlobPath(absl::string_view sha256) const;

  // file_name: the client's name; only its last path component is kept.
  absl::StatusOr<std::unique_ptr<SceneUpload>> BeginUpload(absl::string_view file_name);
  absl::StatusOr<std::optional<SceneRecord>> Find(const std::string& sha256) const;
  int64_t max_bytes() const { return max_bytes_; }

 private:
  friend class SceneUpload;
  std::filesystem::path dir_;
  JobStore* db_;
  const Clock* clock_;
  int64_t max_bytes_;
};

}  // namespace wavebake
