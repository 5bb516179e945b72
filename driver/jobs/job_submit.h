#pragma once
// Submitting a bake (DESIGN.md §4 Submit, UploadScene): SCENE is a built-in
// (`builtin:NAME`) or a scene file, which the coordinator stores once by
// content hash — a file it already has is not sent again.
#include <string>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "driver/jobs/client.h"
#include "proto/bake_request.h"  // ToBakeRequest, kDefaultMaxAttempts
#include "wavebake.pb.h"

namespace wavebake::driver {

struct SceneFile {
  std::string bytes;
  std::string sha256;     // 64 lowercase hex digits
  std::string file_name;  // the last path component: its extension picks the loader
};

bool IsBuiltinScene(const std::string& scene);

// The SCENE argument's file; InvalidArgument naming it when unreadable.
absl::StatusOr<SceneFile> ReadSceneFile(const std::string& path);

// Submits `request` for `scene` (the request's own scene is replaced). A
// file's hash goes first; only if the coordinator does not know it are the
// bytes uploaded, then the job is submitted again. A JSON scene goes with the
// mesh files it names (each by its own hash, SceneRef.files) unless
// with_files is false (the embedded bake, whose planner and workers read the
// user's own paths).
absl::StatusOr<v1::Job> SubmitScene(const Client& client, v1::BakeRequest request,
                                    const std::string& scene, bool with_files = true);

// A bake of `params` (proto/bake_request.h ToBakeRequest) submitted for
// `scene` as SubmitScene does, with the request's output name and attempts.
absl::StatusOr<v1::Job> SubmitBake(const Client& client, const BakeParams& params,
                                   const std::string& output_name, int max_attempts,
                                   const std::string& scene);

}  // namespace wavebake::driver
