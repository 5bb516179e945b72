#include "driver/job_submit.h"

#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "coordinator/scene_store.h"
#include "driver/client.h"

namespace wavebake::driver {
namespace {

constexpr size_t kChunkBytes = 1 << 20;  // as the coordinator streams them back

absl::StatusOr<v1::SceneRef> Upload(const Client& client, const SceneFile& file) {
  std::unique_ptr<grpc::ClientContext> ctx = client.Call(10 * 60'000);
  v1::SceneRef ref;
  std::unique_ptr<grpc::ClientWriter<v1::SceneChunk>> writer =
      client.jobs().UploadScene(ctx.get(), &ref);
  size_t offset = 0;
  do {  // an empty file is one empty chunk: the coordinator then names the problem
    v1::SceneChunk chunk;
    if (offset == 0) {
      chunk.set_file_name(file.file_name);
      chunk.set_sha256(file.sha256);
    }
    chunk.set_offset(static_cast<int64_t>(offset));
    chunk.set_data(file.bytes.substr(offset, kChunkBytes));
    if (!writer->Write(chunk)) break;  // the server ended the call; Finish says why
    offset += kChunkBytes;
  } while (offset < file.bytes.size());
  writer->WritesDone();
  if (grpc::Status s = writer->Finish(); !s.ok()) return FromGrpc(s);
  return ref;
}

absl::StatusOr<v1::Job> Submit(const Client& client, const v1::BakeRequest& request) {
  v1::Job job;
  if (grpc::Status s = client.jobs().Submit(client.Call().get(), request, &job); !s.ok())
    return FromGrpc(s);
  return job;
}

// Submit's answer for a hash the coordinator has never seen (job_service.cc).
bool SceneUnknown(const absl::Status& s) {
  return absl::IsInvalidArgument(s) &&
         absl::StartsWith(s.message(), "scene.uploaded.sha256: no uploaded scene");
}

}  // namespace

bool IsBuiltinScene(const std::string& scene) { return scene.starts_with("builtin:"); }

absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path) {
  absl::StatusOr<std::string> bytes = ReadTextFile(path, "SCENE");
  if (!bytes.ok()) return bytes.status();
  SceneFile file{.bytes = *std::move(bytes),
                 .sha256 = "",
                 .file_name = std::filesystem::path(path).filename().string()};
  file.sha256 = Sha256Hex(file.bytes);
  return file;
}

absl::StatusOr<v1::Job> SubmitScene(const Client& client, v1::BakeRequest request,
                                    const std::string& scene) {
  if (IsBuiltinScene(scene)) {
    request.mutable_scene()->set_builtin(scene);
    return Submit(client, request);
  }
  absl::StatusOr<SceneFile> file = ReadSceneFile(scene);
  if (!file.ok()) return file.status();
  v1::SceneRef* ref = request.mutable_scene()->mutable_uploaded();
  ref->set_sha256(file->sha256);
  ref->set_file_name(file->file_name);
  absl::StatusOr<v1::Job> job = Submit(client, request);
  if (!SceneUnknown(job.status())) return job;
  absl::StatusOr<v1::SceneRef> uploaded = Upload(client, *file);
  if (!uploaded.ok()) return uploaded.status();
  return Submit(client, request);
}

}  // namespace wavebake::driver
