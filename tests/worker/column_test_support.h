#pragma once
// Helpers of the column-stage tests: scratch directories, a bake context for
// a small job, the synthetic matrix of tests/testing/synthetic_columns.h
// as staging written directly in the staging format
// (storage/store/store_layout.h, core/bake/job_plan.h) with ZarrArray, and the
// independent python reader.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/bake/bake_params.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"
#include "tests/testing/synthetic_columns.h"
#include "worker/tiles/bake_context.h"

namespace wavebake::column_testing {

using test_support::ScratchDir;

// A context for builtin:furnace with `layout` (default camera:32x32): the
// scene only supplies the plan and samples; the tests' staging is synthetic.
std::unique_ptr<BakeContext> MakeContext(const BakeParams& params,
                                         const std::string& layout = "camera:32x32");

using test_support::ColumnImage;
using test_support::KindOf;
using test_support::SyntheticKind;
using test_support::SyntheticMatrix;

// Writes staging/transport and staging/tile_energy for `plan` exactly as
// BAKE_TILE does (zero padding rows in the last group, tile-major cells,
// per-tile Σ of squares in double stored as float32).
void WriteSyntheticStaging(const JobPlan& plan, const std::filesystem::path& store,
                           const ColumnImage& image);

// Runs TransformColumns on every group in `order` (empty = 0..groups−1).
void TransformAll(const BakeContext& ctx, const std::filesystem::path& store,
                  std::vector<int> order = {});

using test_support::ReadTree;

struct ProcessResult {
  int exit_code = -1;
  std::string output;
};
// /usr/bin/python3 `script` in `work_dir`; no interpreter is a failure, not a skip.
ProcessResult RunPython(const std::filesystem::path& work_dir, const std::string& script);

}  // namespace wavebake::column_testing
