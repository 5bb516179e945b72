#pragma once
// Shared helpers of the coordinator tests: a temporary directory, a fake
// planner, a job request.

#include <filesystem>
#include <string>

#include "coordinator/scheduling/job_types.h"
#include "tests/testing/scratch_dir.h"
#include "wavebake.pb.h"

namespace wavebake::testing {

using TempDir = test_support::ScratchDir;

inline PlannedJob Plan(int tiles, int groups, std::string store_path = "job.wbk") {
  return {.tiles = tiles,
          .groups = groups,
          .total_rays_estimate = tiles * 1000,
          .store_path = store_path};
}

inline v1::BakeRequest BuiltinRequest(std::string name = "builtin:furnace") {
  v1::BakeRequest r;
  r.mutable_scene()->set_builtin(std::move(name));
  return r;
}

inline std::string Serialized(const v1::BakeRequest& r) {
  std::string s;
  r.SerializeToString(&s);
  return s;
}

}  // namespace wavebake::testing
