#pragma once
// The coordinator's real planner and cleanup (DESIGN.md §2, §4), the two
// callbacks Coordinator::Start takes.
//
// Planning loads the scene (a built-in, or the uploaded bytes under the data
// dir) and cuts the job into BAKE_TILE and TRANSFORM_COLUMNS tasks with the
// same arithmetic the workers use (core/bake/job_plan.h), from the layout's grid
// size alone: no ray is traced in the coordinator. A scene that does not load
// is INVALID_ARGUMENT naming the scene field. Planning also reserves the job's
// partial store directory (proto/bake_request.h PartialStorePath), so two
// jobs can never build into the same one.
//
// Cleanup removes a FAILED or CANCELLED job's partial directory and anything
// at its store path.
#include <filesystem>
#include <map>
#include <string>

#include "absl/status/statusor.h"
#include "coordinator/scheduling/job_types.h"
#include "core/scene/scene.h"
#include "wavebake.pb.h"

namespace wavebake {

struct PlannerOptions {
  std::filesystem::path data_dir;    // uploaded scenes live at SceneStore::BlobPath(data_dir, sha)
  std::filesystem::path store_root;  // where the job's partial directory is reserved
  // Uploaded scenes this process can also read where they came from, by
  // sha256 → LoadScene spec. The embedded `wavebake bake` plans a file scene
  // in place (a JSON scene's meshes are found beside it).
  std::map<std::string, std::string> local_scenes;
  // An update bake's old store (BakeRequest.update_from) is a path of this
  // machine: only the embedded bake, whose client is the machine's user,
  // takes one from its client. Others take the one the service resolved
  // from update_job (coordinator/service/update_job.h).
  bool local_updates = false;
};

PlanFn MakeJobPlanner(PlannerOptions options);
CleanupFn MakeJobCleanup(std::filesystem::path store_root);

// The scene of a request, loaded and checked; errors start with the scene
// field ("scene.builtin: ...", "scene.uploaded: ...").
absl::StatusOr<Scene> LoadRequestScene(const v1::BakeRequest& request,
                                       const PlannerOptions& options);

// Rays BAKE_TILE will trace, roughly: every sample traces K jittered
// directions per texel of the M = `columns` (6N² for the cube, N² for a
// plane light domain), and about half the texels of a receiver are below
// its horizon (never traced).
int64_t EstimateRays(int64_t samples, int columns, int supersample);

}  // namespace wavebake
