#include "storage/zarr/array_spec.h"

#include <zstd.h>

#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

// Each chunk is one zstd frame that numcodecs and our readers decode into one
// buffer; a cap keeps a typo in `chunks` from asking for terabytes.
constexpr int64_t kMaxChunkBytes = int64_t{1} << 31;

absl::Status Bad(absl::string_view source, absl::string_view field, absl::string_view why) {
  return absl::InvalidArgumentError(absl::StrCat(source, ": field \"", field, "\" ", why));
}

// Whether obj[key] exists and equals `value` (JSON equality never throws,
// unlike json::value() on a field of the wrong type).
bool FieldIs(const nlohmann::json& obj, const char* key, const nlohmann::json& value) {
  const auto it = obj.find(key);
  return it != obj.end() && *it == value;
}

// Product of dims, or -1 if it overflows int64.
int64_t Product(const std::vector<int64_t>& dims) {
  int64_t p = 1;
  for (int64_t d : dims) {
    if (d != 0 && p > std::numeric_limits<int64_t>::max() / d) return -1;
    p *= d;
  }
  return p;
}

nlohmann::json FillValueJson(const ArraySpec& spec) {
  if (IsInteger(spec.dtype)) return static_cast<int64_t>(spec.fill_value);
  // Zarr v2 spells non-finite float fill values as strings.
  if (std::isnan(spec.fill_value)) return "NaN";
  if (std::isinf(spec.fill_value)) return spec.fill_value > 0 ? "Infinity" : "-Infinity";
  return spec.fill_value;
}

absl::StatusOr<double> ParseFillValue(const nlohmann::json& j, absl::string_view source) {
  if (j.is_null()) return 0.0;  // "no fill value": missing chunks are undefined; we use 0
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "NaN") return std::numeric_limits<double>::quiet_NaN();
    if (s == "Infinity") return std::numeric_limits<double>::infinity();
    if (s == "-Infinity") return -std::numeric_limits<double>::infinity();
  }
  return Bad(source, "fill_value", absl::StrCat("is not a number: ", j.dump()));
}

absl::StatusOr<std::vector<int64_t>> ParseDims(const nlohmann::json& zarray, absl::string_view key,
                                               absl::string_view source) {
  const auto it = zarray.find(key);
  if (it == zarray.end() || !it->is_array()) return Bad(source, key, "must be an array");
  std::vector<int64_t> dims;
  for (const nlohmann::json& d : *it) {
    if (!d.is_number_integer()) return Bad(source, key, "must hold integers");
    dims.push_back(d.get<int64_t>());
  }
  return dims;
}

absl::StatusOr<int> ParseCompressor(const nlohmann::json& zarray, absl::string_view source) {
  const auto it = zarray.find("compressor");
  if (it == zarray.end() || !it->is_object() || !FieldIs(*it, "id", "zstd")) {
    return Bad(source, "compressor", "must be {\"id\": \"zstd\", ...}");
  }
  // Other keys (a newer numcodecs' "checksum") do not change how frames decode.
  const auto level = it->find("level");
  if (level == it->end()) return kDefaultZstdLevel;
  if (!level->is_number_integer()) return Bad(source, "compressor.level", "must be an integer");
  return level->get<int>();
}

struct Filters {
  bool delta = false, shuffle = false;
};

// null, [], [delta], [shuffle] or [delta, shuffle] (the order they encode in).
absl::StatusOr<Filters> ParseFilters(const nlohmann::json& zarray, DType dtype,
                                     absl::string_view source) {
  const auto it = zarray.find("filters");
  if (it == zarray.end() || it->is_null() || (it->is_array() && it->empty())) return Filters{};
  const std::string name(ZarrName(dtype));
  const auto is_delta = [&](const nlohmann::json& f) {
    return f.is_object() && FieldIs(f, "id", "delta") && FieldIs(f, "dtype", name) &&
           (!f.contains("astype") || FieldIs(f, "astype", name));
  };
  const auto is_shuffle = [&](const nlohmann::json& f) {
    return f.is_object() && FieldIs(f, "id", "shuffle") &&
           FieldIs(f, "elementsize", static_cast<int>(ItemSize(dtype)));
  };
  if (it->is_array() && it->size() <= 2) {
    Filters out;
    size_t k = 0;
    if (k < it->size() && is_delta((*it)[k])) out.delta = true, ++k;
    if (k < it->size() && is_shuffle((*it)[k])) out.shuffle = true, ++k;
    if (k == it->size()) return out;
  }
  return Bad(source, "filters",
             absl::StrCat("unsupported (only null, delta of dtype ", name,
                          " and/or shuffle of its size, in that order): ", it->dump()));
}

// Reads and checks every field; FromZarray catches any json exception left.
absl::StatusOr<ArraySpec> ParseZarray(const nlohmann::json& zarray, absl::string_view source) {
  if (!zarray.is_object())
    return absl::InvalidArgumentError(absl::StrCat(source, ": not an object"));
  if (!FieldIs(zarray, "zarr_format", 2)) return Bad(source, "zarr_format", "must be 2");
  if (!FieldIs(zarray, "order", "C")) return Bad(source, "order", "must be \"C\"");
  if (zarray.contains("dimension_separator") && !FieldIs(zarray, "dimension_separator", ".")) {
    return Bad(source, "dimension_separator", "must be \".\"");
  }
  ArraySpec spec;
  absl::StatusOr<std::vector<int64_t>> shape = ParseDims(zarray, "shape", source);
  if (!shape.ok()) return shape.status();
  absl::StatusOr<std::vector<int64_t>> chunks = ParseDims(zarray, "chunks", source);
  if (!chunks.ok()) return chunks.status();
  spec.shape = *std::move(shape);
  spec.chunks = *std::move(chunks);
  const auto dtype_it = zarray.find("dtype");
  if (dtype_it == zarray.end() || !dtype_it->is_string())
    return Bad(source, "dtype", "must be a string");
  absl::StatusOr<DType> dtype = ParseDType(dtype_it->get<std::string>());
  if (!dtype.ok()) return Bad(source, "dtype", dtype.status().message());
  spec.dtype = *dtype;
  absl::StatusOr<double> fill = ParseFillValue(
      zarray.contains("fill_value") ? zarray.at("fill_value") : nlohmann::json(), source);
  if (!fill.ok()) return fill.status();
  spec.fill_value = *fill;
  absl::StatusOr<int> level = ParseCompressor(zarray, source);
  if (!level.ok()) return level.status();
  spec.zstd_level = *level;
  absl::StatusOr<Filters> filters = ParseFilters(zarray, spec.dtype, source);
  if (!filters.ok()) return filters.status();
  spec.delta_filter = filters->delta;
  spec.shuffle_filter = filters->shuffle;
  if (absl::Status s = ValidateSpec(spec, source); !s.ok()) return s;
  return spec;
}

}  // namespace

bool SameSpec(const ArraySpec& a, const ArraySpec& b) {
  const bool same_fill =
      a.fill_value == b.fill_value || (std::isnan(a.fill_value) && std::isnan(b.fill_value));
  return a.shape == b.shape && a.chunks == b.chunks && a.dtype == b.dtype && same_fill &&
         a.zstd_level == b.zstd_level && a.delta_filter == b.delta_filter &&
         a.shuffle_filter == b.shuffle_filter;
}

absl::Status ValidateSpec(const ArraySpec& spec, absl::string_view source) {
  if (spec.shape.empty()) return Bad(source, "shape", "must have at least one dimension");
  if (spec.chunks.size() != spec.shape.size()) {
    return Bad(
        source, "chunks",
        absl::StrCat("has ", spec.chunks.size(), " dimensions, shape has ", spec.shape.size()));
  }
  for (size_t d = 0; d < spec.shape.size(); ++d) {
    if (spec.shape[d] < 0) return Bad(source, "shape", "must not be negative");
    if (spec.chunks[d] < 1) return Bad(source, "chunks", "must be positive");
  }
  if (Product(spec.shape) < 0) return Bad(source, "shape", "overflows int64 elements");
  const int64_t chunk = Product(spec.chunks);
  if (chunk < 0 || chunk > kMaxChunkBytes / static_cast<int64_t>(ItemSize(spec.dtype))) {
    return Bad(source, "chunks", absl::StrCat("exceed ", kMaxChunkBytes, " bytes per chunk"));
  }
  if (!Representable(spec.dtype, spec.fill_value)) {
    return Bad(source, "fill_value",
               absl::StrCat(spec.fill_value, " is not a value of dtype ", ZarrName(spec.dtype)));
  }
  if (spec.zstd_level < ZSTD_minCLevel() || spec.zstd_level > ZSTD_maxCLevel()) {
    return Bad(source, "compressor.level", absl::StrCat(spec.zstd_level, " is not a zstd level"));
  }
  if (spec.delta_filter && !IsInteger(spec.dtype)) {
    return Bad(source, "filters", "delta is exact only on integer dtypes");
  }
  return absl::OkStatus();
}

int64_t ElementCount(const ArraySpec& spec) { return Product(spec.shape); }
int64_t ChunkElementCount(const ArraySpec& spec) { return Product(spec.chunks); }

std::vector<int64_t> ChunkGrid(const ArraySpec& spec) {
  std::vector<int64_t> grid(spec.shape.size());
  for (size_t d = 0; d < grid.size(); ++d) {
    grid[d] = (spec.shape[d] + spec.chunks[d] - 1) / spec.chunks[d];
  }
  return grid;
}

nlohmann::json ToZarray(const ArraySpec& spec) {
  const std::string dtype(ZarrName(spec.dtype));
  nlohmann::json filters = nullptr;
  if (spec.delta_filter || spec.shuffle_filter) filters = nlohmann::json::array();
  if (spec.delta_filter) filters.push_back({{"id", "delta"}, {"dtype", dtype}, {"astype", dtype}});
  if (spec.shuffle_filter)
    filters.push_back({{"id", "shuffle"}, {"elementsize", static_cast<int>(ItemSize(spec.dtype))}});
  return {
      {"zarr_format", 2},
      {"shape", spec.shape},
      {"chunks", spec.chunks},
      {"dtype", dtype},
      {"compressor", {{"id", "zstd"}, {"level", spec.zstd_level}}},
      {"fill_value", FillValueJson(spec)},
      {"order", "C"},
      {"filters", filters},
      {"dimension_separator", "."},
  };
}

absl::StatusOr<ArraySpec> FromZarray(const nlohmann::json& zarray, absl::string_view source) {
  try {
    return ParseZarray(zarray, source);
  } catch (const nlohmann::json::exception& e) {
    return absl::InvalidArgumentError(absl::StrCat(source, ": malformed: ", e.what()));
  }
}

}  // namespace wavebake
