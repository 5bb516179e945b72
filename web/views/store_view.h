#pragma once
// How a store's relit grid becomes the relight view's picture, by layout
// (DESIGN.md §1 "Spatial layout"):
//   camera   the grid is the camera's image;
//   uv       the grid is the lightmap (a texture over the mesh's UV atlas),
//            shown with its charts dilated into their gutters, as `relight`
//            writes it (runtime/io/lightmap.h);
//   grid, hilbert  the grid holds vertex colours, drawn on the scene's mesh
//            (runtime/io/vertex_raster.h) from the scene's camera or a framing one.
// A layout added later picks its picture in PictureKindOf, the one hook.
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "runtime/relight/store_relight.h"

namespace wavebake::web {

enum class PictureKind { kGridImage, kLightmap, kVertexColours };

// By the layout spec's name ("camera:64x64" → kGridImage). Unknown names
// show the grid as it is.
PictureKind PictureKindOf(std::string_view layout);
const char* PictureKindName(PictureKind kind);  // "camera image", "lightmap", "vertex colours"

class StoreView {
 public:
  virtual ~StoreView() = default;
  virtual PictureKind kind() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // cells_rgb: the relit grid [3·W·H] (NaN masked) → out [3·width·height]
  // linear RGB, NaN where nothing is shown.
  virtual void Render(std::span<const float> cells_rgb, std::span<float> out) const = 0;
};

// `scene` loads the store's scene; only vertex-colour pictures call it.
// The view may keep pointers into `store`, which must outlive it.
// Vertex pictures are `picture_size` pixels on their long side.
absl::StatusOr<std::unique_ptr<StoreView>> MakeStoreView(
    const OpenedStore& store, const std::function<absl::StatusOr<Scene>()>& scene,
    int picture_size = 256);

}  // namespace wavebake::web
