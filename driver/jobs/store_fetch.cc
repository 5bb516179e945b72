#include "driver/jobs/store_fetch.h"

#include <fstream>
#include <optional>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "storage/files/scoped_dir.h"
#include "storage/store/store_verify.h"

namespace wavebake::driver {
namespace {

// A relative path inside the store: no root, no "..", no empty name.
bool SafeRelative(const std::string& path) {
  const std::filesystem::path p(path);
  if (path.empty() || p.is_absolute()) return false;
  for (const auto& part : p)
    if (part == ".." || part == "." || part.empty()) return false;
  return true;
}

// Writes the stream's files under `dir`, checking order and sizes.
absl::StatusOr<FetchSummary> Receive(grpc::ClientReader<v1::FileChunk>& reader,
                                     const std::filesystem::path& dir) {
  FetchSummary summary;
  std::ofstream file;
  std::string path;
  int64_t offset = 0, size = 0;
  v1::FileChunk chunk;
  while (reader.Read(&chunk)) {
    if (chunk.offset() == 0) {
      if (!SafeRelative(chunk.path()))
        return absl::DataLossError(absl::StrCat("ReadStore: unsafe path \"", chunk.path(), "\""));
      path = chunk.path();
      size = chunk.file_size();
      offset = 0;
      std::error_code ec;
      std::filesystem::create_directories((dir / path).parent_path(), ec);
      file = std::ofstream(dir / path, std::ios::binary | std::ios::trunc);
      if (ec || !file)
        return absl::InternalError(absl::StrCat("cannot write ", (dir / path).string()));
    }
    if (chunk.path() != path || chunk.offset() != offset || chunk.file_size() != size)
      return absl::DataLossError(absl::StrCat("ReadStore: chunk of \"", chunk.path(), "\" at ",
                                              chunk.offset(), " is out of order"));
    file.write(chunk.data().data(), static_cast<std::streamsize>(chunk.data().size()));
    offset += static_cast<int64_t>(chunk.data().size());
    summary.bytes += static_cast<int64_t>(chunk.data().size());
    if (chunk.last()) {
      file.close();
      if (!file || offset != size)
        return absl::DataLossError(
            absl::StrCat("ReadStore: \"", path, "\" has ", offset, " bytes, expected ", size));
      ++summary.files;
      path.clear();
    }
  }
  if (!path.empty())
    return absl::DataLossError(absl::StrCat("ReadStore: \"", path, "\" ended early"));
  return summary;
}

}  // namespace

absl::StatusOr<FetchSummary> FetchStore(const Client& client, const std::string& job_id,
                                        const std::filesystem::path& out) {
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(out, ec)))
    return absl::AlreadyExistsError(absl::StrCat("out: ", out.string(), " already exists"));
  const std::filesystem::path parent = std::filesystem::absolute(out).parent_path();
  if (!std::filesystem::is_directory(parent, ec))
    return absl::InvalidArgumentError(
        absl::StrCat("out: directory ", parent.string(), " does not exist"));
  absl::StatusOr<ScopedDir> temp = ScopedDir::CreateBeside(out, "fetch");
  if (!temp.ok()) return temp.status();
  // mkdtemp makes it private; the store is an ordinary directory once in place.
  std::filesystem::permissions(
      temp->path(),
      std::filesystem::perms::owner_all | std::filesystem::perms::group_read |
          std::filesystem::perms::group_exec | std::filesystem::perms::others_read |
          std::filesystem::perms::others_exec,
      ec);

  v1::JobId id;
  id.set_id(job_id);
  std::unique_ptr<grpc::ClientContext> ctx = client.Call(0);
  std::unique_ptr<grpc::ClientReader<v1::FileChunk>> reader =
      client.jobs().ReadStore(ctx.get(), id);
  absl::StatusOr<FetchSummary> summary = Receive(*reader, temp->path());
  if (!summary.ok()) {
    ctx->TryCancel();
    reader->Finish();
    return summary.status();
  }
  if (grpc::Status s = reader->Finish(); !s.ok()) return FromGrpc(s);
  absl::StatusOr<int> arrays = VerifyStore(temp->path());
  if (!arrays.ok())
    return absl::DataLossError(
        absl::StrCat("fetched store does not verify: ", arrays.status().message()));
  summary->arrays = *arrays;
  std::filesystem::rename(temp->path(), out, ec);
  if (ec)
    return absl::InternalError(absl::StrCat("out: rename to ", out.string(), ": ", ec.message()));
  return summary;
}

}  // namespace wavebake::driver
