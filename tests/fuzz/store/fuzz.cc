// The store readers on a damaged store: a small, valid store is written once;
// each input replaces (or, with the selector's high bit, deletes) one of its
// files — the manifest, a .zarray, a chunk — and the store is read every way
// a client reads one. No crash or hang; what reads is consistent: the CSC
// matrix is well formed, ReadColumn agrees with ReadTransport, and a store
// VerifyStore passes also reads whole.
#include <cmath>
#include <iterator>
#include <map>

#include "core/bake/bake_params.h"
#include "storage/store/params_json.h"
#include "storage/store/store_check.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/store/store_samples.h"
#include "storage/store/store_verify.h"
#include "storage/zarr/zarr_array.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {
namespace {

constexpr int kN = 8, kM = 6 * kN * kN, kW = 4, kH = 4;

// The files an input may replace, by selector (first byte, low 7 bits).
constexpr const char* kFiles[] = {".zattrs",
                                  ".zgroup",
                                  "transport/indptr/.zarray",
                                  "transport/indptr/0",
                                  "transport/indices/.zarray",
                                  "transport/indices/0",
                                  "transport/data/.zarray",
                                  "transport/data/0",
                                  "transport/depth/0",
                                  "transport/scale/0",
                                  "samples/grid/.zarray",
                                  "samples/grid/0.0",
                                  "samples/position/0.0"};
constexpr size_t kFileCount = sizeof kFiles / sizeof kFiles[0];

template <class T>
void Write(const std::filesystem::path& store, const char* name, const std::vector<T>& v,
           int64_t chunk, bool delta = false) {
  absl::StatusOr<ZarrArray> a =
      ZarrArray::Create(store::Path(store, name), {.shape = {int64_t(v.size())},
                                                   .chunks = {chunk},
                                                   .dtype = DTypeOf<T>(),
                                                   .delta_filter = delta,
                                                   .shuffle_filter = delta});
  Require(a.ok() && a->WriteAll<T>(v).ok(), "template array");
}

std::filesystem::path MakeStore() {
  const std::filesystem::path store = ScratchDir() / "s.wbk";
  BakeParams p;
  p.light_res = kN;
  p.layout = "camera:4x4";
  std::vector<int64_t> indptr(kM + 1, 0);
  std::vector<uint32_t> indices;
  std::vector<int16_t> data;
  std::vector<uint8_t> depth(kM, 0);
  std::vector<float> scale(kM, 0);
  for (int m = 0; m < kM; ++m) {
    if (m % 97 == 0) {  // a few columns of a few coefficients
      for (uint32_t pos : {0u, 1u, 5u, 15u}) {
        indices.push_back(pos);
        data.push_back(static_cast<int16_t>(int(pos) * 7 - 50));
      }
      depth[m] = 2;
      scale[m] = 0.5f;
    }
    indptr[m + 1] = static_cast<int64_t>(indices.size());
  }
  Require(WriteGroup(store).ok() && WriteGroup(store / "transport").ok(), "template groups");
  Require(WriteAttrs(store, {{"format", store::kFormat},
                             {"scene", "builtin:furnace"},
                             {"scene_hash", "0"},
                             {"params", ToJson(p)},
                             {"N", kN},
                             {"W", kW},
                             {"H", kH},
                             {"S", 2},
                             {"M", kM},
                             {"bits", 9},
                             {"stats", {{"nnz", indices.size()}}}})
              .ok(),
          "template manifest");
  Write(store, store::kIndptr, indptr, 100);
  Write(store, store::kIndices, indices, 8, true);
  Write(store, store::kData, data, 8);
  Write(store, store::kDepth, depth, 100);
  Write(store, store::kScale, scale, 100);
  SampleSet s;
  s.width = kW;
  s.height = kH;
  s.grid.assign(kW * kH, -1);
  s.grid[3] = 0;
  s.grid[9] = 1;
  s.position = {{0, 0, 0}, {1, 0, 0}};
  s.normal = {{0, 1, 0}, {0, 1, 0}};
  s.albedo = {{0.5f, 0.5f, 0.5f}, {0.25f, 0.5f, 0.75f}};
  Require(WriteSamples(store, s).ok(), "template samples");
  return store;
}

const std::filesystem::path& Store() {
  static const std::filesystem::path store = MakeStore();
  return store;
}

std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void CheckReads(const std::filesystem::path& store) {
  absl::StatusOr<CompressedColumns> t = ReadTransport(store);
  const bool verified = VerifyStore(store).ok();
  if (verified) Require(t.ok() && ReadSamples(store).ok(), "a verified store reads whole");
  (void)ForeignStoreEntry(store);
  if (!t.ok()) return;
  Require(t->indptr.size() == size_t(t->columns) + 1 && t->indptr.front() == 0, "indptr shape");
  Require(size_t(t->indptr.back()) == t->indices.size() && t->indices.size() == t->values.size(),
          "nnz agrees");
  for (size_t i = 1; i < t->indptr.size(); ++i) Require(t->indptr[i] >= t->indptr[i - 1], "CSC");
  for (uint32_t pos : t->indices) Require(pos < uint32_t(t->width * t->height), "in the grid");
  for (int c : {0, 97, 194, 291}) {
    absl::StatusOr<DecodedColumn> col = ReadColumn(store, c);
    Require(col.ok(), "ReadColumn of a store ReadTransport reads");
    const size_t b = t->indptr[c], e = t->indptr[c + 1];
    Require(col->positions.size() == e - b, "ReadColumn length");
    for (size_t k = 0; k < e - b; ++k) {
      Require(col->positions[k] == t->indices[b + k], "ReadColumn positions");
      Require(col->values[k] == t->values[b + k] ||
                  (std::isnan(col->values[k]) && std::isnan(t->values[b + k])),
              "ReadColumn values");
    }
  }
}

}  // namespace

std::vector<std::string> Seeds() {
  std::vector<std::string> seeds;
  for (size_t i = 0; i < kFileCount; ++i)
    seeds.push_back(std::string(1, char(i)) + Read(Store() / kFiles[i]));
  seeds.push_back(std::string(1, char(0x80 | 7)));  // a data chunk deleted
  return seeds;
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace wavebake::fuzz;
  if (size == 0) return 0;
  const std::filesystem::path file = Store() / kFiles[(data[0] & 0x7f) % kFileCount];
  static std::map<std::filesystem::path, std::string> originals;
  if (!originals.count(file)) originals[file] = Read(file);
  if (data[0] & 0x80) {
    std::filesystem::remove(file);
  } else {
    WriteBytes(file, std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
  }
  CheckReads(Store());
  WriteBytes(file, originals[file]);
  return 0;
}
