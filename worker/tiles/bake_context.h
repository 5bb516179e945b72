#pragma once
// Everything a worker derives once per job from (scene, params) before it
// runs any task: the checked scene, its samples, the Embree scene, the jitter
// pattern and the plan. Deterministic in its inputs, so every worker (and a
// restarted one) derives the same context. Read-only once built: tasks share
// it across threads.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/bake/bake_gather.h"
#include "core/bake/bake_params.h"
#include "core/bake/job_plan.h"
#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/layouts/layout.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "core/scene/scene_check.h"
#include "core/transport/ray_caster.h"
#include "core/transport/refine_plan.h"
#include "storage/scene_files/scene_files.h"

namespace wavebake {

struct RowReuse;  // worker/tiles/row_reuse.h

struct BakeContext {
  explicit BakeContext(RayCaster c) : caster(std::move(c)) {}

  std::string scene_spec;  // as given: builtin:NAME or a file path
  Scene scene;
  std::string scene_hash;
  SceneReport scene_report;
  BakeParams params;
  LayoutSpec layout;
  SampleSet samples;
  JobPlan plan;
  Cubemap cubemap{8};
  JitterPattern jitter;
  std::optional<RefinePlan> refine;  // params.refine: the rows are traced by refinement
  float epsilon = 0;                 // ray offset along the normal (DESIGN.md §1)
  // params.bounces != 0: the gather operators (core/bake/bake_gather.h), the
  // same for every bounce and on every worker; a camera layout's include its
  // auxiliary set (plan.aux_samples of them).
  std::optional<BakeGathers> bounce;
  // params.bounces auto: the choice (plan.bounces holds the count).
  std::optional<AutoBounceChoice> auto_bounces;
  RayCaster caster;
  // An update bake (worker/tiles/row_reuse.h): the rows BAKE_TILE copies from an
  // old store instead of tracing them; null for a full bake.
  std::shared_ptr<const RowReuse> reuse;
};

// Loads and checks the scene (reading only what `files` allows, null: a local
// scene, storage/scene_files/scene_files.h), validates params (errors name the field),
// lays out the samples and builds the ray caster.
absl::StatusOr<std::unique_ptr<BakeContext>> MakeBakeContext(std::string_view scene_spec,
                                                             const BakeParams& params,
                                                             const SceneFiles* files = nullptr);

}  // namespace wavebake
