#include "core/bake/job_plan.h"

#include <algorithm>

namespace wavebake {

int AutoGroupSize(int columns, int cells) {
  int group = kMaxAutoGroup;
  while (group > 1 && int64_t{group} * cells * int64_t{sizeof(float)} > kAutoGroupImageBytes)
    group /= 2;
  return std::min(group, columns);
}

JobPlan MakeJobPlan(const BakeParams& p, int width, int height) {
  JobPlan plan;
  plan.width = width;
  plan.height = height;
  plan.tile_w = std::min(p.tile_size, width);
  plan.tile_h = std::min(p.tile_size, height);
  plan.tiles_x = width / plan.tile_w;
  plan.tiles_y = height / plan.tile_h;
  plan.light_res = p.light_res;
  plan.columns = p.light_domain.Columns(p.light_res);
  plan.group_size = p.column_group > 0 ? std::min(p.column_group, plan.columns)
                                       : AutoGroupSize(plan.columns, width * height);
  plan.groups = (plan.columns + plan.group_size - 1) / plan.group_size;
  plan.bounces = p.bounces;
  return plan;
}

}  // namespace wavebake
