// The `hilbert` layout: any mesh, its vertices threaded onto the grid by two
// Hilbert curves (3D to order them, 2D to place them).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "absl/strings/str_cat.h"
#include "core/layouts/layout.h"
#include "core/layouts/layout_hilbert_curve.h"
#include "core/scene/scene_check.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace {

constexpr int kKeyBits = 21;  // per axis: 63-bit keys, far finer than any mesh

// Quantizes into the bounding *cube* (largest extent on every axis), so the
// curve's notion of "near" is isotropic even for flat scenes.
std::vector<uint64_t> HilbertKeys(const std::vector<Vec3>& positions, const Bounds3& box) {
  const Vec3 e = box.extent();
  const double side = std::max(
      {static_cast<double>(e.x), static_cast<double>(e.y), static_cast<double>(e.z), 1e-30});
  const double cells = static_cast<double>(1u << kKeyBits);
  auto quantize = [&](float v, float lo) {
    const double q = std::floor((static_cast<double>(v) - lo) / side * cells);
    return static_cast<uint32_t>(std::clamp(q, 0.0, cells - 1));
  };
  std::vector<uint64_t> keys;
  keys.reserve(positions.size());
  for (Vec3 p : positions)
    keys.push_back(HilbertKey3(quantize(p.x, box.lo.x), quantize(p.y, box.lo.y),
                               quantize(p.z, box.lo.z), kKeyBits));
  return keys;
}

}  // namespace

absl::StatusOr<SampleSet> HilbertLayout(const Scene& scene, int width, int height) {
  const std::string name = absl::StrCat("layout 'hilbert:", width, "x", height, "'");
  if (!IsPowerOfTwoIn(width, 1, 4096) || !IsPowerOfTwoIn(height, 1, 4096))
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": width and height must be powers of two in 1..4096"));
  SampleSet s;
  s.width = width;
  s.height = height;
  for (const Mesh& m : scene.meshes) {
    if (m.normals.size() != m.positions.size())
      return absl::FailedPreconditionError(absl::StrCat(
          name, ": mesh '", m.name, "' has not been through CheckAndRepairScene (no normals)"));
    s.position.insert(s.position.end(), m.positions.begin(), m.positions.end());
    s.normal.insert(s.normal.end(), m.normals.begin(), m.normals.end());
    s.albedo.insert(s.albedo.end(), m.positions.size(), m.albedo);
  }
  const int64_t cells = int64_t{width} * height;
  if (static_cast<int64_t>(s.position.size()) > cells)
    return absl::InvalidArgumentError(absl::StrCat(name, ": scene '", scene.name, "' has ",
                                                   s.position.size(), " vertices, more than the ",
                                                   cells, " cells; use a larger grid"));
  const std::vector<uint64_t> keys = HilbertKeys(s.position, SceneBounds(scene));
  std::vector<int32_t> order(s.position.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int32_t a, int32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  // Packed at the start of the curve: the masked cells form one tail region
  // rather than holes scattered through the image.
  const std::vector<int32_t> curve = HilbertCurveCells(width, height);
  s.grid.assign(static_cast<size_t>(cells), -1);
  for (size_t k = 0; k < order.size(); ++k) s.grid[curve[k]] = order[k];
  s.vertex.resize(s.position.size());
  std::iota(s.vertex.begin(), s.vertex.end(), 0);
  return s;
}

}  // namespace wavebake
