#include "storage/store/store_root_marker.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "nlohmann/json.hpp"
#include "storage/files/json_file.h"

namespace wavebake {
namespace {

constexpr char kFormat[] = "wavebake-store-root/1";

std::string RandomId() {
  std::random_device random;
  std::string id;
  for (int i = 0; i < 4; ++i) absl::StrAppendFormat(&id, "%08x", random());
  return id;
}

std::string Describe(const std::filesystem::path& root) {
  return absl::StrCat("--store-root ", root.string());
}

// The marker of the same name one level down, if any: the usual slip is the
// coordinator's --data dir instead of its store/ below it.
std::string Hint(const std::filesystem::path& root) {
  std::error_code ec;
  for (const char* sub : {"store"}) {
    if (std::filesystem::exists(root / sub / kStoreRootMarker, ec)) {
      return absl::StrCat(" (did you mean ", (root / sub).string(), "?)");
    }
  }
  return "";
}

// Creates and removes a file: the worker writes stores here, and a read-only
// mount or missing permission should stop it before its first task.
absl::Status CheckWritable(const std::filesystem::path& root) {
  const std::filesystem::path probe =
      root / absl::StrCat(".write-probe-", ::getpid(), "-", RandomId().substr(0, 8));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    return absl::FailedPreconditionError(absl::StrCat(
        Describe(root), ": not writable (", std::strerror(errno),
        "); expected the coordinator's store root, read-write: workers write the stores there"));
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::string> ReadStoreRootMarker(const std::filesystem::path& root) {
  absl::StatusOr<nlohmann::json> j = ReadJsonFile(root / kStoreRootMarker);
  if (!j.ok()) return j.status();
  if (!j->is_object() || j->value("format", "") != kFormat || !(*j)["id"].is_string()) {
    return absl::FailedPreconditionError(
        absl::StrCat((root / kStoreRootMarker).string(), ": not a ", kFormat, " marker"));
  }
  return (*j)["id"].get<std::string>();
}

absl::StatusOr<std::string> EnsureStoreRootMarker(const std::filesystem::path& root) {
  absl::StatusOr<std::string> id = ReadStoreRootMarker(root);
  if (!absl::IsNotFound(id.status())) return id;
  // Written to a temp file, then linked into place: link() fails if another
  // coordinator got there first, and then its id is the one.
  const std::string fresh = RandomId();
  const std::filesystem::path temp = root / absl::StrCat(".", kStoreRootMarker, ".", fresh);
  if (absl::Status s =
          WriteJsonFile(temp, {{"format", kFormat},
                               {"id", fresh},
                               {"note", "written by the wavebake coordinator; workers check it"}});
      !s.ok()) {
    return s;
  }
  const int linked = ::link(temp.c_str(), (root / kStoreRootMarker).c_str());
  const int err = errno;
  std::error_code ec;
  std::filesystem::remove(temp, ec);
  if (linked == 0) return fresh;
  if (err == EEXIST) return ReadStoreRootMarker(root);
  return absl::InternalError(absl::StrCat("store root ", root.string(), ": cannot write ",
                                          kStoreRootMarker, ": ", std::strerror(err)));
}

absl::Status CheckWorkerStoreRoot(const std::filesystem::path& root,
                                  const std::string& expected_id) {
  const std::string expected = expected_id.empty()
                                   ? std::string("the coordinator's store root")
                                   : absl::StrCat("the coordinator's store root, whose ",
                                                  kStoreRootMarker, " holds id ", expected_id);
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) {
    return absl::FailedPreconditionError(absl::StrCat(
        Describe(root), ": no such directory (is the shared filesystem mounted?); expected ",
        expected));
  }
  if (expected_id.empty()) return CheckWritable(root);  // a coordinator that writes no marker
  absl::StatusOr<std::string> id = ReadStoreRootMarker(root);
  if (absl::IsNotFound(id.status())) {
    return absl::FailedPreconditionError(absl::StrCat(Describe(root), ": no ", kStoreRootMarker,
                                                      " here, so this is no store root", Hint(root),
                                                      "; expected ", expected));
  }
  if (!id.ok()) {
    return absl::FailedPreconditionError(
        absl::StrCat(Describe(root), ": ", id.status().message(), "; expected ", expected));
  }
  if (*id != expected_id) {
    return absl::FailedPreconditionError(
        absl::StrCat(Describe(root), ": the store root of another coordinator (", kStoreRootMarker,
                     " holds id ", *id, ")", Hint(root), "; expected ", expected));
  }
  return CheckWritable(root);
}

}  // namespace wavebake
