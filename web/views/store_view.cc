#include "web/views/store_view.h"

#include <algorithm>
#include <limits>

#include "absl/strings/str_cat.h"
#include "runtime/io/lightmap.h"
#include "runtime/io/vertex_raster.h"

namespace wavebake::web {
namespace {

class GridImageView final : public StoreView {
 public:
  GridImageView(PictureKind kind, int w, int h) : kind_(kind), w_(w), h_(h) {}
  PictureKind kind() const override { return kind_; }
  int width() const override { return w_; }
  int height() const override { return h_; }
  void Render(std::span<const float> cells, std::span<float> out) const override {
    std::copy(cells.begin(), cells.end(), out.begin());
  }

 private:
  PictureKind kind_;
  int w_, h_;
};

// A uv store's grid is the lightmap; it is shown as `relight --out x.png`
// writes it, its charts dilated into their gutters (runtime/io/lightmap.h).
class LightmapView final : public StoreView {
 public:
  explicit LightmapView(const SampleSet* samples) : samples_(samples) {}
  PictureKind kind() const override { return PictureKind::kLightmap; }
  int width() const override { return samples_->width; }
  int height() const override { return samples_->height; }
  void Render(std::span<const float> cells, std::span<float> out) const override {
    const std::vector<float> dilated = DilateGutters(*samples_, cells);
    std::copy(dilated.begin(), dilated.end(), out.begin());
  }

 private:
  const SampleSet* samples_;  // the opened store's, which outlives the view
};

class VertexColourView final : public StoreView {
 public:
  VertexColourView(VertexRaster raster, std::vector<int32_t> vertex_of_cell)
      : raster_(std::move(raster)),
        vertex_of_cell_(std::move(vertex_of_cell)),
        colours_(3 * static_cast<size_t>(raster_.vertices())) {}
  PictureKind kind() const override { return PictureKind::kVertexColours; }
  int width() const override { return raster_.width(); }
  int height() const override { return raster_.height(); }
  void Render(std::span<const float> cells, std::span<float> out) const override {
    std::fill(colours_.begin(), colours_.end(), std::numeric_limits<float>::quiet_NaN());
    for (size_t cell = 0; cell < vertex_of_cell_.size(); ++cell) {
      const int32_t v = vertex_of_cell_[cell];
      if (v < 0) continue;
      for (int c = 0; c < 3; ++c) colours_[3 * v + c] = cells[3 * cell + c];
    }
    raster_.Shade(colours_, out);
  }

 private:
  VertexRaster raster_;
  std::vector<int32_t> vertex_of_cell_;  // global vertex id per cell, −1 for none
  mutable std::vector<float> colours_;   // callers serialize frames per store
};

}  // namespace

PictureKind PictureKindOf(std::string_view layout) {
  if (layout.starts_with("grid") || layout.starts_with("hilbert"))
    return PictureKind::kVertexColours;
  if (layout.starts_with("uv")) return PictureKind::kLightmap;
  return PictureKind::kGridImage;
}

const char* PictureKindName(PictureKind kind) {
  switch (kind) {
    case PictureKind::kLightmap:
      return "lightmap";
    case PictureKind::kVertexColours:
      return "vertex colours";
    default:
      return "camera image";
  }
}

absl::StatusOr<std::unique_ptr<StoreView>> MakeStoreView(
    const OpenedStore& store, const std::function<absl::StatusOr<Scene>()>& load_scene,
    int picture_size) {
  const SampleSet& s = store.samples;
  const PictureKind kind = PictureKindOf(store.info.params.layout);
  if (kind == PictureKind::kLightmap) return std::make_unique<LightmapView>(&store.samples);
  if (kind != PictureKind::kVertexColours || s.vertex.size() != s.position.size()) {
    return std::make_unique<GridImageView>(
        kind == PictureKind::kVertexColours ? PictureKind::kGridImage : kind, s.width, s.height);
  }
  absl::StatusOr<Scene> scene = load_scene();
  if (!scene.ok()) return scene.status();
  absl::StatusOr<VertexRaster> raster =
      VertexRaster::Create(*scene, PictureCamera(*scene), picture_size, picture_size);
  if (!raster.ok()) return raster.status();
  std::vector<int32_t> vertex_of_cell(s.grid.size(), -1);
  for (size_t cell = 0; cell < s.grid.size(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) continue;
    const int32_t v = s.vertex[id];
    if (v < 0 || v >= raster->vertices()) {
      return absl::DataLossError(absl::StrCat("samples/vertex: ", v, " outside the ",
                                              raster->vertices(), " vertices of the scene"));
    }
    vertex_of_cell[cell] = v;
  }
  return std::make_unique<VertexColourView>(*std::move(raster), std::move(vertex_of_cell));
}

}  // namespace wavebake::web
