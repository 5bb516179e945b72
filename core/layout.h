#pragma once
// Spatial layouts (DESIGN.md §1 "Spatial layout"): where each spatial sample
// sits on the W×H grid whose column images the column transform compresses.
// This file: the `layout` spec and the two mesh layouts; the camera layout
// (ray casting) lives elsewhere.
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/samples.h"
#include "core/scene.h"

namespace wavebake {

enum class LayoutKind { kCamera, kGrid, kHilbert };

struct LayoutSpec {
  LayoutKind kind = LayoutKind::kCamera;
  // Powers of two in 1..4096. For kGrid both are 0: the grid mesh decides.
  int width = 64, height = 64;
};

// `camera` (= camera:64x64) | `camera:WxH` | `grid` | `hilbert:WxH`. Errors
// name the `layout` field and say what is wrong.
absl::StatusOr<LayoutSpec> ParseLayout(std::string_view spec);
// The canonical spelling, which ParseLayout reads back: "camera:64x64", "grid",
// "hilbert:128x64".
std::string ToString(const LayoutSpec& spec);

// Vertex (i, j) of the scene's first regular-grid mesh is cell (x=i, y=j) and
// sample id y*W + x; W×H are the mesh's grid dims (powers of two ≤ 4096). No
// cell is masked. `vertex` holds global vertex ids: all meshes' vertices
// numbered in mesh order. The scene must have passed CheckAndRepairScene.
absl::StatusOr<SampleSet> GridLayout(const Scene& scene);

// Every vertex of every mesh is a sample, and sample id = global vertex id.
// Vertices are ordered by a 3D Hilbert key of their position (quantized in the
// scene's bounding cube; ties by id) and placed in that order along a 2D
// Hilbert curve through the W×H grid, so neighbours in space tend to be
// neighbours on the grid; the curve's tail stays masked (−1). For W ≠ H the
// curve runs through consecutive min(W,H)-square blocks along the long side
// (see HilbertCurveCells). Error if there are more vertices than cells.
absl::StatusOr<SampleSet> HilbertLayout(const Scene& scene, int width, int height);

}  // namespace wavebake
