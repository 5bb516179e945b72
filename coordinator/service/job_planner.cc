#include "coordinator/service/job_planner.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <system_error>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "coordinator/state/scene_store.h"
#include "core/bake/bake_gather.h"
#include "core/bake/job_plan.h"
#include "core/layouts/layout.h"
#include "core/layouts/sample_layout.h"
#include "proto/bake_request.h"
#include "storage/files/atomic_file.h"
#include "storage/scene_files/scene_bundle.h"
#include "storage/scene_files/scene_files.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {
namespace {

// The loaders pick the format by the file's extension, but an uploaded scene
// is stored under its hash alone: plan it through a link that carries the
// uploaded file name, <data dir>/scene-names/<sha256>/<file name>.
absl::StatusOr<std::string> NamedBlob(const v1::SceneRef& ref, const PlannerOptions& options) {
  std::string name = std::filesystem::path(ref.file_name()).filename().string();
  if (name.empty() || name == "." || name == "..") name = "scene";
  const std::filesystem::path blob = SceneStore::BlobPath(options.data_dir, ref.sha256());
  const std::filesystem::path dir = options.data_dir / "scene-names" / ref.sha256();
  const std::filesystem::path link = dir / name;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!ec && !std::filesystem::is_symlink(link, ec)) {
    std::filesystem::create_symlink(std::filesystem::absolute(blob), link, ec);
    if (ec && std::filesystem::is_symlink(link)) ec.clear();  // a concurrent plan made it
  }
  if (ec)
    return absl::InternalError(absl::StrCat("scene link ", link.string(), ": ", ec.message()));
  return link.string();
}

// A scene uploaded with its files (storage/scene_files/scene_bundle.h): a directory of
// links to their blobs under <data dir>/scene-bundles, and a JSON scene may
// name nothing else.
absl::StatusOr<std::string> BundledScene(const v1::SceneRef& ref, const PlannerOptions& options) {
  std::string name = std::filesystem::path(ref.file_name()).filename().string();
  if (name.empty() || name.front() == '.') name = "scene";
  std::vector<BundleFile> files;
  std::vector<std::pair<std::string, std::string>> keyed;
  for (const v1::SceneFileRef& f : ref.files()) {
    files.push_back({f.path(), SceneStore::BlobPath(options.data_dir, f.sha256())});
    keyed.emplace_back(f.path(), f.sha256());
  }
  absl::StatusOr<std::filesystem::path> scene =
      MaterializeBundle(options.data_dir / "scene-bundles", BundleKey(ref.sha256(), keyed), name,
                        SceneStore::BlobPath(options.data_dir, ref.sha256()), files);
  if (!scene.ok()) return scene.status();
  if (scene->extension() == ".json") {
    if (absl::Status s = CheckJsonSceneInBundle(*scene, files); !s.ok())
      return absl::InvalidArgumentError(absl::StrCat("scene.uploaded: scene file '", name,
                                                     "' (sha256 ", ref.sha256().substr(0, 12),
                                                     "…): ", s.message()));
  }
  return scene->string();
}

absl::Status SceneError(const char* field, const absl::Status& s) {
  return absl::InvalidArgumentError(absl::StrCat(field, ": ", s.message()));
}

// Reserves the job's partial directory and marks it (proto/bake_request.h
// kPartialMarker). A directory already there belongs to another job.
absl::Status ReservePartialStore(const std::filesystem::path& store_root,
                                 const std::string& output_name) {
  const std::filesystem::path partial = store_root / PartialStorePath(output_name);
  std::error_code ec;
  std::filesystem::create_directories(partial.parent_path(), ec);
  const bool created = !ec && std::filesystem::create_directory(partial, ec);
  if (!ec && !created) {
    return absl::AlreadyExistsError(
        absl::StrCat("output_name: \"", output_name, "\" is being built by another job"));
  }
  if (ec)
    return absl::InternalError(absl::StrCat("store root: ", partial.string(), ": ", ec.message()));
  const std::filesystem::path marker = partial / kPartialMarker;
  // A full disk is ResourceExhausted, as everywhere (storage/files/atomic_file.h);
  // the directory is not left reserved: it would block this name for good.
  if (absl::Status s = AtomicWriteText(marker, "wavebake partial store\n"); !s.ok()) {
    std::filesystem::remove_all(partial, ec);
    return absl::Status(s.code(), absl::StrCat("store root: ", s.message()));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<Scene> LoadRequestScene(const v1::BakeRequest& request,
                                       const PlannerOptions& options) {
  if (request.scene().has_builtin()) {
    absl::StatusOr<Scene> scene = LoadScene(absl::StrCat("builtin:", BuiltinSceneName(request)));
    if (!scene.ok()) return SceneError("scene.builtin", scene.status());
    return scene;
  }
  const v1::SceneRef& ref = request.scene().uploaded();
  auto local = options.local_scenes.find(ref.sha256());
  if (local != options.local_scenes.end()) {  // the user's own path: its errors name it
    SceneReport report;
    absl::StatusOr<Scene> scene = LoadScene(local->second, &report);
    if (!scene.ok()) return SceneError("scene.uploaded", scene.status());
    for (const std::string& w : report.warnings) spdlog::warn("{}", w);
    return scene;
  }
  // A JSON scene always loads from its bundle, even an empty one: its mesh
  // paths then never reach this host's own files.
  const bool bundle =
      !ref.files().empty() || std::filesystem::path(ref.file_name()).extension() == ".json";
  absl::StatusOr<std::string> named = bundle ? BundledScene(ref, options) : NamedBlob(ref, options);
  if (!named.ok()) return named.status();
  // Only what was uploaded: messages name files relative to it, never a
  // path of this machine (storage/scene_files/scene_files.h).
  const std::unique_ptr<SceneFiles> files =
      ConfinedSceneFiles(std::filesystem::path(*named).parent_path());
  absl::StatusOr<Scene> scene = LoadScene(*named, nullptr, files.get());
  if (!scene.ok()) {
    std::string message(scene.status().message());
    const std::string name = files->Name(*named);
    const std::string file =
        absl::StrCat("'", name, "' (sha256 ", ref.sha256().substr(0, 12), "…)");
    if (absl::StrReplaceAll({{absl::StrCat("'", name, "'"), file}}, &message) == 0)
      message = absl::StrCat(file, ": ", message);
    return absl::InvalidArgumentError(absl::StrCat("scene.uploaded: ", message));
  }
  return scene;
}

int64_t EstimateRays(int64_t samples, int columns, int supersample) {
  // K is rounded up to a square (core/directions/jitter_pattern.h).
  const int64_t strata = static_cast<int64_t>(std::ceil(std::sqrt(double(supersample)) - 1e-9));
  return samples * columns * strata * strata / 2;
}

PlanFn MakeJobPlanner(PlannerOptions options) {
  return [options =
              std::move(options)](const v1::BakeRequest& request) -> absl::StatusOr<PlannedJob> {
    absl::StatusOr<BakeParams> params = ToBakeParams(request);
    if (!params.ok()) return params.status();
    // Input from a remote client never names a file of the server.
    // An update's old store is a path only for the embedded bake; a
    // coordinator's client names a job instead, which the service resolved
    // into update_from and update_scene (coordinator/service/update_job.h).
    if (!params->update_from.empty() && !options.local_updates && !request.has_update_scene())
      return absl::InvalidArgumentError(
          "update_from: a coordinator takes no store path from a client; name the old job "
          "with update_job (`wavebake submit NEW --update JOB_OR_STORE`)");
    absl::StatusOr<LayoutSpec> layout = ParseLayout(params->layout);
    if (!layout.ok()) return layout.status();
    absl::StatusOr<Scene> scene = LoadRequestScene(request, options);
    if (!scene.ok()) return scene.status();
    absl::StatusOr<std::pair<int, int>> grid = LayoutGridSize(*scene, *layout);
    if (!grid.ok()) return grid.status();
    const auto [width, height] = *grid;
    JobPlan plan = MakeJobPlan(*params, width, height);
    // A camera's bounces gather from the meshes' vertices, baked as tiles of
    // their own (core/bake/bake_gather.h).
    plan.aux_samples = AuxSampleCount(*scene, *params, *layout);
    // Samples that will trace: every vertex for hilbert (the rest of its grid
    // is masked); the covered texels for uv, whose rasterization also refuses
    // an atlas that is no lightmap before any worker starts; every cell
    // otherwise (camera: an upper bound, misses are masked).
    int64_t samples = int64_t{width} * height;
    if (layout->kind == LayoutKind::kHilbert) {
      samples = 0;
      for (const Mesh& m : scene->meshes) samples += static_cast<int64_t>(m.positions.size());
    } else if (layout->kind == LayoutKind::kUv) {
      absl::StatusOr<SampleSet> texels = UvLayout(*scene, *layout);
      if (!texels.ok()) return texels.status();
      samples = texels->size();
    }
    if (absl::Status s = ReservePartialStore(options.store_root, request.output_name()); !s.ok())
      return s;
    return PlannedJob{.tiles = plan.all_tiles(),
                      .groups = plan.groups,
                      .total_rays_estimate = EstimateRays(samples + plan.aux_samples, plan.columns,
                                                          params->supersample),
                      .store_path = {}};  // the request's output_name
  };
}

CleanupFn MakeJobCleanup(std::filesystem::path store_root) {
  return [root = std::move(store_root)](const JobRecord& job) {
    for (const std::filesystem::path& dir :
         {root / PartialStorePath(job.store_path), root / job.store_path}) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
      if (ec) spdlog::warn("job {}: cannot remove {}: {}", job.id, dir.string(), ec.message());
    }
  };
}

}  // namespace wavebake
