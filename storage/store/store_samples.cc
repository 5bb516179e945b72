#include "storage/store/store_samples.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {
namespace {

constexpr int64_t kRowsPerChunk = 1 << 16;

std::vector<float> Flatten(const std::vector<Vec3>& v) {
  std::vector<float> out;
  out.reserve(v.size() * 3);
  for (const Vec3& p : v) out.insert(out.end(), {p.x, p.y, p.z});
  return out;
}

std::vector<Vec3> Unflatten(const std::vector<float>& f) {
  std::vector<Vec3> out(f.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

template <class T>
absl::Status WriteArray(const std::filesystem::path& store, const char* name, ArraySpec spec,
                        const std::vector<T>& values) {
  spec.dtype = DTypeOf<T>();
  absl::StatusOr<ZarrArray> a = ZarrArray::Create(store::Path(store, name), spec);
  if (!a.ok()) return a.status();
  return a->WriteAll<T>(values);
}

ArraySpec Vec3Spec(int64_t rows) {
  return {.shape = {rows, 3}, .chunks = {std::max<int64_t>(1, std::min(rows, kRowsPerChunk)), 3}};
}

template <class T>
absl::StatusOr<std::vector<T>> ReadArray(const std::filesystem::path& store, const char* name,
                                         const std::vector<int64_t>& shape) {
  absl::StatusOr<ZarrArray> a = ZarrArray::OpenComplete(store::Path(store, name));
  if (!a.ok()) return a.status();
  if (a->spec().shape != shape)
    return absl::DataLossError(absl::StrCat(a->dir().string(), ": shape [",
                                            absl::StrJoin(a->spec().shape, ", "), "], expected [",
                                            absl::StrJoin(shape, ", "), "]"));
  absl::StatusOr<std::vector<T>> values = a->ReadAll<T>();
  if (!values.ok()) return values;
  if constexpr (std::is_floating_point_v<T>) {
    // A NaN or infinite position, normal or albedo poisons its sample's
    // relit value (NaN passed for success); a finished store has none.
    const int64_t row = shape.size() == 2 ? shape[1] : 1;
    for (size_t i = 0; i < values->size(); ++i) {
      if (std::isfinite((*values)[i])) continue;
      return absl::DataLossError(absl::StrCat(a->dir().string(), "[", int64_t(i) / row,
                                              row > 1 ? absl::StrCat(", ", int64_t(i) % row) : "",
                                              "] = ", (*values)[i], " is not finite"));
    }
  }
  return values;
}

absl::Status WriteUvCharts(const std::filesystem::path& store, const std::vector<UvChart>& charts) {
  const int64_t n = static_cast<int64_t>(charts.size());
  std::vector<int32_t> rects;
  std::vector<float> domains;
  for (const UvChart& c : charts) {
    rects.insert(rects.end(), {c.x, c.y, c.width, c.height});
    domains.insert(domains.end(), {c.u0, c.v0, c.u1, c.v1});
  }
  const ArraySpec spec{.shape = {n, 4}, .chunks = {n, 4}};
  if (absl::Status s = WriteArray<int32_t>(store, store::kUvRects, spec, rects); !s.ok()) return s;
  return WriteArray<float>(store, store::kUvDomains, spec, domains);
}

// Names from the manifest's "uv" entry (worker/columns/store_manifest.cc).
absl::StatusOr<std::vector<UvChart>> ReadUvCharts(const std::filesystem::path& store,
                                                  const nlohmann::json& attrs, int width,
                                                  int height) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kUvRects));
  if (!a.ok()) return a.status();
  const int64_t n = a->spec().shape.at(0);
  absl::StatusOr<std::vector<int32_t>> rects = ReadArray<int32_t>(store, store::kUvRects, {n, 4});
  if (!rects.ok()) return rects.status();
  absl::StatusOr<std::vector<float>> domains = ReadArray<float>(store, store::kUvDomains, {n, 4});
  if (!domains.ok()) return domains.status();
  std::vector<UvChart> charts(n);
  for (int64_t i = 0; i < n; ++i) {
    const int32_t* r = rects->data() + 4 * i;
    const float* d = domains->data() + 4 * i;
    charts[i] = {"", r[0], r[1], r[2], r[3], d[0], d[1], d[2], d[3]};
    if (r[0] < 0 || r[1] < 0 || r[2] <= 0 || r[3] <= 0 || r[0] + r[2] > width ||
        r[1] + r[3] > height || !(d[0] < d[2]) || !(d[1] < d[3]))
      return absl::DataLossError(absl::StrCat(store::Path(store, store::kUvRects).string(),
                                              ": chart ", i, " is outside the ", width, "x", height,
                                              " lightmap or has an empty UV domain"));
    const nlohmann::json* meshes = attrs.contains("uv") ? &attrs["uv"]["meshes"] : nullptr;
    if (meshes != nullptr && meshes->is_array() && i < int64_t(meshes->size()))
      charts[i].mesh = (*meshes)[i].value("name", "");
  }
  return charts;
}

}  // namespace

absl::Status WriteSamples(const std::filesystem::path& store, const SampleSet& samples) {
  if (absl::Status s = WriteGroup(store::Path(store, store::kSamples)); !s.ok()) return s;
  const int64_t h = samples.height, w = samples.width, n = samples.size();
  const ArraySpec grid{.shape = {h, w},
                       .chunks = {std::min<int64_t>(h, 256), std::min<int64_t>(w, 256)}};
  if (absl::Status s = WriteArray<int32_t>(store, store::kGrid, grid, samples.grid); !s.ok())
    return s;
  for (auto [name, values] :
       {std::pair{store::kPosition, &samples.position}, std::pair{store::kNormal, &samples.normal},
        std::pair{store::kAlbedo, &samples.albedo}}) {
    if (absl::Status s = WriteArray<float>(store, name, Vec3Spec(n), Flatten(*values)); !s.ok())
      return s;
  }
  if (!samples.uv_charts.empty()) {
    if (absl::Status s = WriteUvCharts(store, samples.uv_charts); !s.ok()) return s;
  }
  if (samples.vertex.empty()) return absl::OkStatus();
  const ArraySpec vertex{.shape = {n},
                         .chunks = {std::max<int64_t>(1, std::min(n, kRowsPerChunk))}};
  return WriteArray<int32_t>(store, store::kVertex, vertex, samples.vertex);
}

absl::StatusOr<SampleSet> ReadSamples(const std::filesystem::path& store) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  SampleSet s;
  s.width = info->width;
  s.height = info->height;
  absl::StatusOr<std::vector<int32_t>> grid =
      ReadArray<int32_t>(store, store::kGrid, {s.height, s.width});
  if (!grid.ok()) return grid.status();
  s.grid = *std::move(grid);
  absl::StatusOr<ZarrArray> position = ZarrArray::Open(store::Path(store, store::kPosition));
  if (!position.ok()) return position.status();
  const int64_t n = info->samples >= 0 ? info->samples : position->spec().shape.at(0);
  for (auto [name, out] :
       {std::pair{store::kPosition, &s.position}, std::pair{store::kNormal, &s.normal},
        std::pair{store::kAlbedo, &s.albedo}}) {
    absl::StatusOr<std::vector<float>> v = ReadArray<float>(store, name, {n, 3});
    if (!v.ok()) return v.status();
    *out = Unflatten(*v);
  }
  if (std::filesystem::exists(store::Path(store, store::kVertex))) {
    absl::StatusOr<std::vector<int32_t>> v = ReadArray<int32_t>(store, store::kVertex, {n});
    if (!v.ok()) return v.status();
    s.vertex = *std::move(v);
  }
  if (std::filesystem::exists(store::Path(store, store::kUvRects))) {
    absl::StatusOr<std::vector<UvChart>> charts =
        ReadUvCharts(store, info->attrs, s.width, s.height);
    if (!charts.ok()) return charts.status();
    s.uv_charts = *std::move(charts);
  }
  for (int32_t id : s.grid) {
    if (id < -1 || id >= n)
      return absl::DataLossError(absl::StrCat(store::Path(store, store::kGrid).string(),
                                              ": sample id ", id, " outside -1..", n - 1));
  }
  return s;
}

}  // namespace wavebake
