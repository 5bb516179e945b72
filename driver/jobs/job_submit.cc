#include "driver/jobs/job_submit.h"

#include <filesystem>
#include <set>
#include <utility>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "coordinator/state/scene_store.h"
#include "driver/jobs/client.h"
#include "storage/scene_files/scene_bundle.h"
#include "storage/scene_files/scene_loader.h"

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

// Submit's answer for a hash the coordinator has never seen (job_service.cc),
// the scene's or one of its files'.
bool SceneUnknown(const absl::Status& s) {
  return absl::IsInvalidArgument(s) &&
         (absl::StartsWith(s.message(), "scene.uploaded.sha256: no uploaded scene") ||
          (absl::StartsWith(s.message(), "scene.uploaded.files[") &&
           absl::StrContains(s.message(), "sha256: no uploaded scene")));
}

// The files a JSON scene names (meshes[i].file), read relative to it: they
// go up with the scene, so it bakes where none of this machine's paths exist.
// Absolute paths and ".." are refused here, naming the field, as the
// coordinator would refuse them.
absl::StatusOr<std::vector<std::pair<std::string, SceneFile>>> SceneFiles(
    const std::string& scene) {
  std::vector<std::pair<std::string, SceneFile>> out;
  if (std::filesystem::path(scene).extension() != ".json") return out;
  absl::StatusOr<std::vector<std::string>> names = JsonSceneMeshFiles(scene);
  if (!names.ok()) return names.status();
  std::set<std::string> seen;
  for (size_t i = 0; i < names->size(); ++i) {
    const std::string& name = (*names)[i];
    const std::string field = absl::StrCat("SCENE '", scene, "': meshes[", i, "].file");
    if (absl::Status s = CheckBundlePath(name, field); !s.ok()) return s;
    if (!seen.insert(name).second) continue;
    absl::StatusOr<SceneFile> file =
        ReadSceneFile((std::filesystem::path(scene).parent_path() / name).string());
    if (!file.ok())
      return absl::InvalidArgumentError(absl::StrCat(field, ": ", file.status().message()));
    out.emplace_back(name, *std::move(file));
  }
  return out;
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
                                    const std::string& scene, bool with_files) {
  if (IsBuiltinScene(scene)) {
    request.mutable_scene()->set_builtin(scene);
    return Submit(client, request);
  }
  absl::StatusOr<SceneFile> file = ReadSceneFile(scene);
  if (!file.ok()) return file.status();
  absl::StatusOr<std::vector<std::pair<std::string, SceneFile>>> files =
      with_files ? SceneFiles(scene) : std::vector<std::pair<std::string, SceneFile>>{};
  if (!files.ok()) return files.status();
  v1::SceneRef* ref = request.mutable_scene()->mutable_uploaded();
  ref->set_sha256(file->sha256);
  ref->set_file_name(file->file_name);
  for (const auto& [path, f] : *files) {
    v1::SceneFileRef* r = ref->add_files();
    r->set_path(path);
    r->set_sha256(f.sha256);
  }
  absl::StatusOr<v1::Job> job = Submit(client, request);
  if (!SceneUnknown(job.status())) return job;
  // Uploads are by content: what the coordinator has already costs one pass.
  for (const auto& [path, f] : *files) {
    absl::StatusOr<v1::SceneRef> uploaded = Upload(client, f);
    if (!uploaded.ok()) return uploaded.status();
  }
  absl::StatusOr<v1::SceneRef> uploaded = Upload(client, *file);
  if (!uploaded.ok()) return uploaded.status();
  return Submit(client, request);
}

absl::StatusOr<v1::Job> SubmitBake(const Client& client, const BakeParams& params,
                                   const std::string& output_name, int max_attempts,
                                   const std::string& scene) {
  v1::BakeRequest request = ToBakeRequest(params);
  request.set_output_name(output_name);
  request.set_max_attempts(max_attempts);
  return SubmitScene(client, std::move(request), scene);
}

}  // namespace wavebake::driver
