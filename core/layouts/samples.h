#pragma once
// Spatial samples laid on a W×H grid (DESIGN.md §1 "Spatial layout"): the
// rows of T. A column of T is then an image over this grid.
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace wavebake {

// Where one mesh's UV atlas lies in a `uv` layout's lightmap (core/layouts/uv_atlas.h):
// the UV domain [u0, u1] × [v0, v1] (v up) fills the texel rectangle whose
// top-left texel is (x, y), row 0 at the top of the lightmap.
struct UvChart {
  std::string mesh;
  int x = 0, y = 0, width = 0, height = 0;
  float u0 = 0, v0 = 0, u1 = 1, v1 = 1;
};

struct SampleSet {
  int width = 0, height = 0;       // powers of two
  std::vector<int32_t> grid;       // [height*width], sample id or -1 (masked cell)
  std::vector<Vec3> position;      // [S]
  std::vector<Vec3> normal;        // [S], unit
  std::vector<Vec3> albedo;        // [S], RGB
  std::vector<int32_t> vertex;     // [S] global mesh vertex id (mesh layouts), else empty
  std::vector<UvChart> uv_charts;  // uv layouts: one per mesh, in mesh order; else empty

  int size() const { return static_cast<int>(position.size()); }
  int cells() const { return width * height; }
};

}  // namespace wavebake
