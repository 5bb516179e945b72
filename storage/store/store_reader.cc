#include "storage/store/store_reader.h"

#include <cmath>
#include <span>

#include "absl/strings/str_cat.h"
#include "core/columns/quantizer.h"
#include "core/layouts/layout.h"
#include "core/scene/scene_hash.h"
#include "core/util/power_of_two.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/store/params_json.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_scene.h"
#include "storage/zarr/array_range.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {
namespace {

absl::Status BadAttr(const std::filesystem::path& store, const std::string& key,
                     const std::string& why) {
  return absl::InvalidArgumentError(
      absl::StrCat((store / ".zattrs").string(), ": ", key, ": ", why));
}

absl::Status GetPositiveInt(const std::filesystem::path& store, const nlohmann::json& attrs,
                            const char* key, int* out) {
  if (!attrs.contains(key) || !attrs[key].is_number_integer() || attrs[key].get<int64_t>() <= 0 ||
      attrs[key].get<int64_t>() > (1 << 20)) {
    return BadAttr(store, key, "missing or not a positive integer");
  }
  *out = attrs[key].get<int>();
  return absl::OkStatus();
}

absl::Status CheckInfo(const std::filesystem::path& store, const StoreInfo& info) {
  if (!IsPowerOfTwo(info.width) || !IsPowerOfTwo(info.height))
    return BadAttr(store, "W/H",
                   absl::StrCat(info.width, "x", info.height, " is not a power-of-two grid"));
  if (info.light_res != info.params.light_res)
    return BadAttr(store, "N", absl::StrCat(info.light_res, " differs from params.light_res"));
  if (info.bits < 2 || info.bits > 16)
    return BadAttr(store, "bits", absl::StrCat(info.bits, " is outside 2..16"));
  if (info.attrs.contains("M") && info.attrs["M"] != info.columns)
    return BadAttr(store, "M",
                   absl::StrCat(info.attrs["M"].dump(), " is not 6·N² = ", info.columns));
  return absl::OkStatus();
}

absl::StatusOr<ZarrArray> OpenShaped(const std::filesystem::path& store, const char* name,
                                     DType dtype, int64_t length) {
  absl::StatusOr<ZarrArray> a = ZarrArray::OpenComplete(store::Path(store, name));
  if (!a.ok()) return a.status();
  if (a->spec().dtype != dtype || a->spec().shape.size() != 1 ||
      (length >= 0 && a->spec().shape[0] != length)) {
    return absl::DataLossError(absl::StrCat(a->dir().string(), ": dtype or shape is not ",
                                            ZarrName(dtype), " [", length, "]"));
  }
  return a;
}

// The five CSC arrays of a store, opened and checked against M (DESIGN.md §3).
struct TransportArrays {
  ZarrArray indptr, indices, data, depth, scale;
  int64_t nnz() const { return indices.spec().shape[0]; }
};

absl::StatusOr<TransportArrays> OpenTransport(const std::filesystem::path& store,
                                              const StoreInfo& info) {
  const int m = info.columns;
  absl::StatusOr<ZarrArray> indptr = OpenShaped(store, store::kIndptr, DType::kInt64, m + 1);
  absl::StatusOr<ZarrArray> depth = OpenShaped(store, store::kDepth, DType::kUint8, m);
  absl::StatusOr<ZarrArray> scale = OpenShaped(store, store::kScale, DType::kFloat32, m);
  absl::StatusOr<ZarrArray> indices = OpenShaped(store, store::kIndices, DType::kUint32, -1);
  for (const auto* a : {&indptr, &depth, &scale, &indices})
    if (!a->ok()) return a->status();
  if (info.nnz >= 0 && indices->spec().shape[0] != info.nnz)
    return absl::DataLossError(absl::StrCat(indices->dir().string(), ": ", indices->spec().shape[0],
                                            " entries, the manifest's stats.nnz is ", info.nnz));
  absl::StatusOr<ZarrArray> data =
      OpenShaped(store, store::kData, DType::kInt16, indices->spec().shape[0]);
  if (!data.ok()) return data.status();
  return TransportArrays{*std::move(indptr), *std::move(indices), *std::move(data),
                         *std::move(depth), *std::move(scale)};
}

// Dequantizes one column's codes in place of `values` (DESIGN.md §1: the
// level of each position comes from the column's depth, core/wavelets/subband.h).
absl::Status DecodeColumn(const StoreInfo& info, int column, int depth, float scale,
                          std::span<const uint32_t> positions, std::span<const int16_t> q,
                          std::vector<float>* values) {
  const int cells = info.width * info.height;
  // A NaN or infinite step would decode to a column of NaN or inf that turns
  // every relit pixel the column touches into NaN, reported as success.
  if (!std::isfinite(scale))
    return absl::DataLossError(absl::StrCat(store::kScale, "[", column, "] = ", scale,
                                            " is not a finite quantization step"));
  if (depth > MaxDepth(info.width, info.height))
    return absl::DataLossError(absl::StrCat("transport/depth[", column, "] = ", depth,
                                            " exceeds the grid's maximum depth"));
  std::vector<uint8_t> levels(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    if (positions[i] >= static_cast<uint32_t>(cells))
      return absl::DataLossError(absl::StrCat("transport/indices: position ", positions[i],
                                              " of column ", column, " is outside the grid"));
    levels[i] = static_cast<uint8_t>(SubbandAt(positions[i] % info.width, positions[i] / info.width,
                                               info.width, info.height, depth)
                                         .level);
  }
  values->resize(positions.size());
  Dequantize(q, positions, levels, info.params.level_scaling, scale, info.params.seed, column,
             *values);
  // A finite step so large that code × step overflows float is damage too.
  for (size_t i = 0; i < values->size(); ++i) {
    if (!std::isfinite((*values)[i]))
      return absl::DataLossError(absl::StrCat(store::kScale, "[", column, "] = ", scale,
                                              " overflows: entry ", i, " of column ", column,
                                              " decodes to ", (*values)[i]));
  }
  return absl::OkStatus();
}

absl::Status CheckIndptr(std::span<const int64_t> indptr, int64_t nnz) {
  if (indptr.front() != 0 || indptr.back() != nnz)
    return absl::DataLossError("transport/indptr: does not run from 0 to nnz");
  for (size_t i = 1; i < indptr.size(); ++i) {
    if (indptr[i] < indptr[i - 1])
      return absl::DataLossError(absl::StrCat("transport/indptr: decreases at ", i));
  }
  return absl::OkStatus();
}

}  // namespace

std::string StoreSceneHash(const StoreInfo& info, const Scene& scene) {
  absl::StatusOr<LayoutSpec> layout = ParseLayout(info.params.layout);
  const bool uv = layout.ok() && layout->kind == LayoutKind::kUv;
  return SceneHash(scene, uv ? layout->uv_channel : -1);
}

absl::StatusOr<StoreInfo> ReadStoreInfo(const std::filesystem::path& store) {
  if (!std::filesystem::exists(store / ".zgroup"))
    return absl::NotFoundError(absl::StrCat(store.string(), ": not a wavebake store (no .zgroup)"));
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  if (!attrs.ok()) return attrs.status();
  const nlohmann::json& a = *attrs;
  if (!a.contains("format") || !a["format"].is_string())
    return BadAttr(store, "format", absl::StrCat("missing (expected '", store::kFormat, "')"));
  if (a["format"] != store::kFormat)
    return BadAttr(
        store, "format",
        absl::StrCat("'", a["format"].get<std::string>(), "' is not '", store::kFormat, "'"));
  StoreInfo info;
  info.attrs = a;
  absl::StatusOr<BakeParams> params = BakeParamsFromJson(a.value("params", nlohmann::json()));
  if (!params.ok()) return BadAttr(store, "params", std::string(params.status().message()));
  info.params = *params;
  for (const char* key : {"scene", "scene_hash"}) {
    if (!a.contains(key) || !a[key].is_string()) return BadAttr(store, key, "missing");
  }
  info.scene_spec = LocateStoreScene(a["scene"].get<std::string>(), store);
  info.scene_hash = a["scene_hash"].get<std::string>();
  for (auto [key, out] : {std::pair{"W", &info.width}, std::pair{"H", &info.height},
                          std::pair{"N", &info.light_res}, std::pair{"bits", &info.bits}}) {
    if (absl::Status s = GetPositiveInt(store, a, key, out); !s.ok()) return s;
  }
  info.columns = info.params.light_domain.Columns(info.light_res);
  // Optional (hand-made stores lack them); wrong types are corruption.
  if (a.contains("S")) {
    if (!a["S"].is_number_integer() || a["S"].get<int64_t>() < 0)
      return BadAttr(store, "S", "not a sample count");
    info.samples = a["S"].get<int64_t>();
  }
  if (a.contains("stats") && a["stats"].is_object() && a["stats"].contains("nnz")) {
    const nlohmann::json& nnz = a["stats"]["nnz"];
    if (!nnz.is_number_integer() || nnz.get<int64_t>() < 0)
      return BadAttr(store, "stats.nnz", "not a coefficient count");
    info.nnz = nnz.get<int64_t>();
  }
  if (absl::Status s = CheckInfo(store, info); !s.ok()) return s;
  return info;
}

absl::StatusOr<CompressedColumns> ReadTransport(const std::filesystem::path& store) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  const int m = info->columns;
  absl::StatusOr<TransportArrays> arrays = OpenTransport(store, *info);
  if (!arrays.ok()) return arrays.status();
  const int64_t nnz = arrays->nnz();

  CompressedColumns out;
  absl::StatusOr<std::vector<int64_t>> indptr = arrays->indptr.ReadAll<int64_t>();
  absl::StatusOr<std::vector<uint8_t>> depth = arrays->depth.ReadAll<uint8_t>();
  absl::StatusOr<std::vector<float>> scale = arrays->scale.ReadAll<float>();
  absl::StatusOr<std::vector<uint32_t>> indices = arrays->indices.ReadAll<uint32_t>();
  absl::StatusOr<std::vector<int16_t>> data = arrays->data.ReadAll<int16_t>();
  for (absl::Status s :
       {indptr.status(), depth.status(), scale.status(), indices.status(), data.status()}) {
    if (!s.ok()) return s;
  }
  if (absl::Status s = CheckIndptr(*indptr, nnz); !s.ok()) return s;
  out.values.reserve(nnz);
  std::vector<float> column_values;
  for (int c = 0; c < m; ++c) {
    const size_t b = (*indptr)[c], e = (*indptr)[c + 1];
    if (absl::Status s =
            DecodeColumn(*info, c, (*depth)[c], (*scale)[c], std::span(*indices).subspan(b, e - b),
                         std::span(*data).subspan(b, e - b), &column_values);
        !s.ok()) {
      return s;
    }
    out.values.insert(out.values.end(), column_values.begin(), column_values.end());
  }
  out.width = info->width;
  out.height = info->height;
  out.light_res = info->light_res;
  out.columns = m;
  out.row_filter = info->params.row_filter;
  out.column_filter = info->params.column_filter;
  out.indptr = *std::move(indptr);
  out.indices = *std::move(indices);
  out.depth = *std::move(depth);
  return out;
}

absl::StatusOr<DecodedColumn> ReadColumn(const std::filesystem::path& store, int column) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (column < 0 || column >= info->columns)
    return absl::InvalidArgumentError(
        absl::StrCat("column: ", column, " is outside 0..", info->columns - 1));
  absl::StatusOr<TransportArrays> arrays = OpenTransport(store, *info);
  if (!arrays.ok()) return arrays.status();
  const int64_t nnz = arrays->nnz();

  absl::StatusOr<std::vector<int64_t>> range =
      ReadRange<int64_t>(arrays->indptr, column, column + 2);
  absl::StatusOr<std::vector<uint8_t>> depth =
      ReadRange<uint8_t>(arrays->depth, column, column + 1);
  absl::StatusOr<std::vector<float>> scale = ReadRange<float>(arrays->scale, column, column + 1);
  for (absl::Status s : {range.status(), depth.status(), scale.status()})
    if (!s.ok()) return s;
  const int64_t b = (*range)[0], e = (*range)[1];
  if (b < 0 || e < b || e > nnz)
    return absl::DataLossError(absl::StrCat("transport/indptr: bad range of column ", column));
  DecodedColumn out;
  absl::StatusOr<std::vector<uint32_t>> positions = ReadRange<uint32_t>(arrays->indices, b, e);
  absl::StatusOr<std::vector<int16_t>> q = ReadRange<int16_t>(arrays->data, b, e);
  for (absl::Status s : {positions.status(), q.status()})
    if (!s.ok()) return s;
  out.depth = (*depth)[0];
  out.positions = *std::move(positions);
  if (absl::Status s =
          DecodeColumn(*info, column, out.depth, (*scale)[0], out.positions, *q, &out.values);
      !s.ok()) {
    return s;
  }
  return out;
}

}  // namespace wavebake
