#pragma once
// Spatial samples laid on a W×H grid (DESIGN.md §1 "Spatial layout"): the
// rows of T. A column of T is then an image over this grid.
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace wavebake {

struct SampleSet {
  int width = 0, height = 0;    // powers of two
  std::vector<int32_t> grid;    // [height*width], sample id or -1 (masked cell)
  std::vector<Vec3> position;   // [S]
  std::vector<Vec3> normal;     // [S], unit
  std::vector<Vec3> albedo;     // [S], RGB
  std::vector<int32_t> vertex;  // [S] global mesh vertex id (mesh layouts), else empty

  int size() const { return static_cast<int>(position.size()); }
  int cells() const { return width * height; }
};

}  // namespace wavebake
