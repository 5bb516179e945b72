#include "coordinator/scheduling/job_types.h"

namespace wavebake {

const char* PhaseName(Phase p) {
  switch (p) {
    case Phase::kQueued:
      return "QUEUED";
    case Phase::kBaking:
      return "BAKING";
    case Phase::kTransforming:
      return "TRANSFORMING";
    case Phase::kFinalizing:
      return "FINALIZING";
    case Phase::kDone:
      return "DONE";
    case Phase::kFailed:
      return "FAILED";
    case Phase::kCancelled:
      return "CANCELLED";
  }
  return "?";
}

const char* TaskKindName(TaskKind k) {
  switch (k) {
    case TaskKind::kBakeTile:
      return "BAKE_TILE";
    case TaskKind::kTransformColumns:
      return "TRANSFORM_COLUMNS";
    case TaskKind::kFinalize:
      return "FINALIZE";
  }
  return "?";
}

}  // namespace wavebake
