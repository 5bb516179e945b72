// The store reader against a store written by hand here, array by array
// (DESIGN.md §3), with its expected values worked out from the dequantization
// formula of DESIGN.md §1 and levels read off the Mallat layout by hand.
#include "storage/store/store_reader.h"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <limits>

#include "absl/strings/str_cat.h"
#include "core/columns/quantizer.h"
#include "storage/store/params_json.h"
#include "storage/store/store_check.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_samples.h"
#include "storage/store/store_verify.h"
#include "storage/zarr/zarr_array.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

constexpr int kN = 8, kM = 6 * kN * kN, kW = 4, kH = 4, kBits = 9;
constexpr uint64_t kSeed = 0x123456789ABCDEFull;

// One hand-made column: positions in a 4×4 Mallat layout, their subband
// levels at the column's depth (0 = LL and the last step's details), codes.
struct HandColumn {
  int column, depth;
  std::vector<uint32_t> positions;
  std::vector<int> levels;
  std::vector<int16_t> q;
  float scale;
};

const std::vector<HandColumn>& Columns() {
  static const std::vector<HandColumn> columns = {
      // depth 2: (0,0) LL, (1,0) step-1 HL → level 0; (2,0), (3,3) step-0 → level 1.
      {0, 2, {0, 1, 2, 15}, {0, 0, 1, 1}, {100, -50, 255, -1}, 2.5f},
      // depth 0: every position is level 0.
      {5, 0, {3, 8}, {0, 0}, {-255, 7}, 0.125f},
      // depth 1: LL and step-0 details are all level 0.
      {200, 1, {0, 3, 12}, {0, 0, 0}, {1, 2, -3}, 1e-3f},
      // depth 2: (2,2) is a step-0 HH coefficient → level 1.
      {383, 2, {10}, {1}, {-17}, 40.0f},
  };
  return columns;
}

float Expected(const HandColumn& c, size_t k) {
  const double u = DitherAt(kSeed, c.column, c.positions[k]);
  // wavebake/2 with level scaling "paper": (q − u)·step·2^−l, `scale` the step.
  return static_cast<float>((c.q[k] - u) * c.scale / std::pow(2.0, c.levels[k]));
}

nlohmann::json Attrs() {
  BakeParams p;
  p.light_res = kN;
  p.seed = kSeed;
  p.bits = kBits;
  p.level_scaling = LevelScaling::kPaper;
  p.layout = "camera:4x4";
  return {{"format", store::kFormat},
          {"scene", "builtin:furnace"},
          {"scene_hash", "abc"},
          {"params", ToJson(p)},
          {"N", kN},
          {"W", kW},
          {"H", kH},
          {"bits", kBits}};
}

template <class T>
void Write(const std::filesystem::path& store, const char* name, const std::vector<T>& v,
           int64_t chunk = 3) {
  absl::StatusOr<ZarrArray> a =
      ZarrArray::Create(store::Path(store, name),
                        {.shape = {int64_t(v.size())}, .chunks = {chunk}, .dtype = DTypeOf<T>()});
  ASSERT_TRUE(a.ok()) << a.status();
  ASSERT_TRUE(a->WriteAll<T>(v).ok());
}

// The CSC arrays of Columns(), small chunks so that columns straddle them.
void WriteStore(const std::filesystem::path& store, std::vector<uint32_t> extra_index = {}) {
  ASSERT_TRUE(WriteGroup(store).ok());
  ASSERT_TRUE(WriteAttrs(store, Attrs()).ok());
  ASSERT_TRUE(WriteGroup(store / "transport").ok());
  std::vector<int64_t> indptr(kM + 1, 0);
  std::vector<uint32_t> indices;
  std::vector<int16_t> data;
  std::vector<uint8_t> depth(kM, 0);
  std::vector<float> scale(kM, 0.0f);
  size_t next = 0;
  for (int m = 0; m < kM; ++m) {
    if (next < Columns().size() && Columns()[next].column == m) {
      const HandColumn& c = Columns()[next++];
      indices.insert(indices.end(), c.positions.begin(), c.positions.end());
      data.insert(data.end(), c.q.begin(), c.q.end());
      depth[m] = c.depth;
      scale[m] = c.scale;
    }
    indptr[m + 1] = indices.size();
  }
  if (!extra_index.empty()) indices[0] = extra_index[0];
  Write(store, store::kIndptr, indptr, 100);
  Write(store, store::kIndices, indices);
  Write(store, store::kData, data);
  Write(store, store::kDepth, depth, 100);
  Write(store, store::kScale, scale, 100);
}

TEST(StoreReaderTest, ReadsInfo) {
  TempDir tmp;
  const auto store = tmp.path() / "s.wbk";
  WriteStore(store);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  ASSERT_TRUE(info.ok()) << info.status();
  EXPECT_EQ(info->width, kW);
  EXPECT_EQ(info->height, kH);
  EXPECT_EQ(info->light_res, kN);
  EXPECT_EQ(info->columns, kM);
  EXPECT_EQ(info->bits, kBits);
  EXPECT_EQ(info->params.seed, kSeed);
  EXPECT_EQ(info->params.layout, "camera:4x4");
  EXPECT_EQ(info->scene_spec, "builtin:furnace");
  EXPECT_EQ(info->scene_hash, "abc");
}

TEST(StoreReaderTest, TransportIsDequantizedAndUnscaled) {
  TempDir tmp;
  const auto store = tmp.path() / "s.wbk";
  WriteStore(store);
  absl::StatusOr<CompressedColumns> t = ReadTransport(store);
  ASSERT_TRUE(t.ok()) << t.status();
  EXPECT_EQ(t->columns, kM);
  EXPECT_EQ(t->width, kW);
  ASSERT_EQ(t->indptr.size(), size_t(kM + 1));
  for (const HandColumn& c : Columns()) {
    EXPECT_EQ(t->depth[c.column], c.depth);
    const int64_t b = t->indptr[c.column];
    ASSERT_EQ(t->indptr[c.column + 1] - b, int64_t(c.positions.size()));
    for (size_t k = 0; k < c.positions.size(); ++k) {
      EXPECT_EQ(t->indices[b + k], c.positions[k]);
      EXPECT_EQ(t->values[b + k], Expected(c, k)) << "column " << c.column << " entry " << k;
    }
    absl::StatusOr<DecodedColumn> one = ReadColumn(store, c.column);
    ASSERT_TRUE(one.ok()) << one.status();
    EXPECT_EQ(one->depth, c.depth);
    EXPECT_EQ(one->positions, c.positions);
    for (size_t k = 0; k < c.positions.size(); ++k) EXPECT_EQ(one->values[k], Expected(c, k));
  }
  absl::StatusOr<DecodedColumn> empty = ReadColumn(store, 1);
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->values.empty());
}

TEST(StoreReaderTest, ErrorsNameTheProblem) {
  TempDir tmp;
  const auto store = tmp.path() / "s.wbk";
  EXPECT_EQ(ReadStoreInfo(store).status().code(), absl::StatusCode::kNotFound);
  WriteStore(store);
  EXPECT_EQ(ReadColumn(store, kM).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(ReadColumn(store, -1).status().message(), HasSubstr("column"));

  nlohmann::json attrs = Attrs();
  attrs["format"] = "wavebake/0";
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  absl::Status s = ReadStoreInfo(store).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("format"));
  EXPECT_THAT(s.message(), HasSubstr("wavebake/0"));
  EXPECT_THAT(s.message(), HasSubstr("wavebake/2"));

  attrs = Attrs();
  attrs["params"]["column_filter"] = "db8";
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  s = ReadStoreInfo(store).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("column_filter"));

  attrs = Attrs();
  attrs["params"]["column_mode"] = "fast";
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  EXPECT_THAT(ReadStoreInfo(store).status().message(), HasSubstr("column_mode"));

  attrs = Attrs();
  attrs["W"] = 3;
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  EXPECT_THAT(ReadStoreInfo(store).status().message(), HasSubstr("W"));

  // A position outside the 4×4 grid is corruption, not a crash.
  TempDir tmp2;
  const auto bad = tmp2.path() / "bad.wbk";
  WriteStore(bad, {16});
  EXPECT_EQ(ReadTransport(bad).status().code(), absl::StatusCode::kDataLoss);
  EXPECT_EQ(ReadColumn(bad, 0).status().code(), absl::StatusCode::kDataLoss);
}

// Zarr reads a missing chunk as the fill value; a finished store must not:
// a deleted data chunk used to relight almost black with rc 0.
TEST(StoreReaderTest, AMissingChunkIsDataLossNamingIt) {
  for (const char* name : {store::kData, store::kIndices, store::kIndptr, store::kScale}) {
    TempDir tmp;
    const auto store = tmp.path() / "s.wbk";
    WriteStore(store);
    const std::filesystem::path chunk = store::Path(store, name) / "0";
    ASSERT_TRUE(std::filesystem::remove(chunk)) << chunk;
    for (absl::Status s : {ReadTransport(store).status(), ReadColumn(store, 0).status()}) {
      EXPECT_EQ(s.code(), absl::StatusCode::kDataLoss) << name << ": " << s;
      EXPECT_THAT(s.message(), HasSubstr(chunk.string())) << s;
    }
  }
}

// A NaN or inf step decodes to NaN/inf everywhere its column reaches: the
// relit image was all NaN with rc 0. A finite step so large that the codes
// overflow is the same damage.
TEST(StoreReaderTest, ANonFiniteOrOverflowingScaleIsDataLossNamingTheColumn) {
  const HandColumn& victim = Columns()[0];
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), 3e38f}) {
    TempDir tmp;
    const auto store = tmp.path() / "s.wbk";
    WriteStore(store);
    std::vector<float> scale(kM, 0.0f);
    for (const HandColumn& c : Columns()) scale[c.column] = c.scale;
    scale[victim.column] = bad;
    Write(store, store::kScale, scale, 100);
    for (absl::Status s :
         {ReadTransport(store).status(), ReadColumn(store, victim.column).status()}) {
      EXPECT_EQ(s.code(), absl::StatusCode::kDataLoss) << bad << ": " << s;
      EXPECT_THAT(s.message(), HasSubstr(absl::StrCat("transport/scale[", victim.column, "]")))
          << s;
    }
    // Another column still reads: the check is per column.
    EXPECT_TRUE(ReadColumn(store, Columns()[1].column).ok());
  }
}

// The same for the per-sample floats: a NaN normal or an inf albedo is
// named by array and index.
TEST(StoreReaderTest, ANonFiniteSampleValueIsDataLossNamingIt) {
  for (const char* name : {store::kPosition, store::kNormal, store::kAlbedo}) {
    TempDir tmp;
    const auto store = tmp.path() / "s.wbk";
    WriteStore(store);
    SampleSet s;
    s.width = kW;
    s.height = kH;
    s.grid.assign(kW * kH, -1);
    for (int i = 0; i < 3; ++i) {
      s.grid[i] = i;
      s.position.push_back({float(i), 0, 0});
      s.normal.push_back({0, 1, 0});
      s.albedo.push_back({0.5f, 0.5f, 0.5f});
    }
    std::vector<Vec3>& victim = std::string(name) == store::kPosition ? s.position
                                : std::string(name) == store::kNormal ? s.normal
                                                                      : s.albedo;
    victim[2].y = std::string(name) == store::kAlbedo ? std::numeric_limits<float>::infinity()
                                                      : std::numeric_limits<float>::quiet_NaN();
    ASSERT_TRUE(WriteSamples(store, s).ok());
    const absl::Status read = ReadSamples(store).status();
    EXPECT_EQ(read.code(), absl::StatusCode::kDataLoss) << name << ": " << read;
    EXPECT_THAT(read.message(), HasSubstr(absl::StrCat(name, "[2, 1]"))) << read;
  }
}

// A FIFO where the reader expects a file: a plain open() blocks until a
// writer comes, and `relight` hung. Every file of the store is opened
// without blocking and refused unless it is a regular file. Should the read
// block after all (the code before this fix), the test opens the FIFO's
// write end to free the reader and fails instead of hanging.
TEST(StoreReaderTest, AFifoInTheStoreIsRefusedWithoutBlocking) {
  for (const std::string& name : {std::string(".zattrs"), std::string(store::kScale) + "/0",
                                  std::string(store::kData) + "/.zarray"}) {
    TempDir tmp;
    const auto store = tmp.path() / "s.wbk";
    WriteStore(store);
    const std::filesystem::path fifo = store / name;
    ASSERT_TRUE(std::filesystem::remove(fifo)) << fifo;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << fifo;
    std::future<absl::Status> read =
        std::async(std::launch::async, [&] { return ReadTransport(store).status(); });
    if (read.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
      // Free the blocked reader: a writer that opens and closes is an EOF.
      const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
      read.wait();
      ADD_FAILURE() << name << ": reading the store blocked on the FIFO";
      continue;
    }
    const absl::Status s = read.get();
    EXPECT_FALSE(s.ok()) << name;
    EXPECT_THAT(s.message(), HasSubstr(fifo.string())) << s;
    EXPECT_THAT(s.message(), HasSubstr("not a regular file (a FIFO)")) << s;
  }
}

TEST(StoreReaderTest, ArraysThatDisagreeWithTheManifestAreDataLoss) {
  TempDir tmp;
  const auto store = tmp.path() / "s.wbk";
  WriteStore(store);
  size_t nnz = 0;
  for (const HandColumn& c : Columns()) nnz += c.positions.size();
  nlohmann::json attrs = Attrs();
  attrs["stats"] = {{"nnz", nnz}};
  attrs["M"] = kM;
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  ASSERT_TRUE(ReadTransport(store).ok());

  attrs["stats"]["nnz"] = nnz + 5;  // FINALIZE wrote more than is there
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  absl::Status s = ReadTransport(store).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(s.message(), HasSubstr("stats.nnz"));
  EXPECT_EQ(ReadColumn(store, 0).status().code(), absl::StatusCode::kDataLoss);

  attrs = Attrs();
  attrs["M"] = kM + 1;
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  EXPECT_THAT(ReadStoreInfo(store).status().message(), HasSubstr("M"));
}

TEST(StoreReaderTest, ParamsRoundTripThroughJson) {
  BakeParams p;
  p.light_res = 64;
  p.layout = "hilbert:128x64";
  p.supersample = 9;
  p.row_filter = WaveletFilter::kDaub4;
  p.column_mode = ColumnMode::kFull;
  p.column_filter = WaveletFilter::kCdf97;
  p.target_error = 0.0123;
  p.error_scope = ErrorScope::kColumn;
  p.column_terms = 17;
  p.bits = 11;
  p.seed = ~0ull;
  p.tile_size = 64;
  p.column_group = 33;
  p.ray_epsilon = 1.5e-4f;
  // Through text, as the .zattrs file carries it.
  absl::StatusOr<BakeParams> back = BakeParamsFromJson(nlohmann::json::parse(ToJson(p).dump()));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->light_res, p.light_res);
  EXPECT_EQ(back->layout, p.layout);
  EXPECT_EQ(back->supersample, p.supersample);
  EXPECT_EQ(back->row_filter, p.row_filter);
  EXPECT_EQ(back->column_mode, p.column_mode);
  EXPECT_EQ(back->column_filter, p.column_filter);
  EXPECT_EQ(back->target_error, p.target_error);
  EXPECT_EQ(back->error_scope, p.error_scope);
  EXPECT_EQ(back->column_terms, p.column_terms);
  EXPECT_EQ(back->bits, p.bits);
  EXPECT_EQ(back->seed, p.seed);
  EXPECT_EQ(back->tile_size, p.tile_size);
  EXPECT_EQ(back->column_group, p.column_group);
  EXPECT_EQ(back->ray_epsilon, p.ray_epsilon);
  EXPECT_EQ(ToJson(BakeParams{})["bits"], "auto");
  // The transport: absent for diffuse (stores stay as they were), spelled
  // out and read back for visibility.
  EXPECT_FALSE(ToJson(BakeParams{}).contains("transport"));
  BakeParams v;
  v.transport = Transport::kVisibility;
  EXPECT_EQ(ToJson(v)["transport"], "visibility");
  absl::StatusOr<BakeParams> vb = BakeParamsFromJson(ToJson(v));
  ASSERT_TRUE(vb.ok()) << vb.status();
  EXPECT_EQ(vb->transport, Transport::kVisibility);
  EXPECT_EQ(BakeParamsFromJson(ToJson(BakeParams{}))->transport, Transport::kDiffuse);
  nlohmann::json bad_transport = ToJson(v);
  bad_transport["transport"] = "glossy";
  EXPECT_THAT(BakeParamsFromJson(bad_transport).status().message(), HasSubstr("transport"));
  // Refinement is recorded when on; a store without the key (every store
  // baked before refinement existed, and --refine off) was brute-forced.
  EXPECT_TRUE(p.refine);
  EXPECT_EQ(ToJson(p)["refine"], "on");
  EXPECT_TRUE(back->refine);
  BakeParams brute = p;
  brute.refine = false;
  EXPECT_FALSE(ToJson(brute).contains("refine"));
  absl::StatusOr<BakeParams> read = BakeParamsFromJson(ToJson(brute));
  ASSERT_TRUE(read.ok());
  EXPECT_FALSE(read->refine);
  nlohmann::json bad = ToJson(p);
  bad["refine"] = "maybe";
  EXPECT_THAT(std::string(BakeParamsFromJson(bad).status().message()),
              ::testing::HasSubstr("params.refine"));
}

TEST(StoreReaderTest, SamplesRoundTrip) {
  TempDir tmp;
  const auto store = tmp.path() / "s.wbk";
  WriteStore(store);
  SampleSet s;
  s.width = kW;
  s.height = kH;
  s.grid.assign(kW * kH, -1);
  for (int i = 0; i < 5; ++i) {
    s.grid[3 * i] = i;
    s.position.push_back({float(i), 0.5f, -1.0f});
    s.normal.push_back({0, 1, 0});
    s.albedo.push_back({0.25f, 0.5f, 0.75f * i});
    s.vertex.push_back(100 + i);
  }
  ASSERT_TRUE(WriteSamples(store, s).ok());
  absl::StatusOr<SampleSet> back = ReadSamples(store);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->grid, s.grid);
  EXPECT_EQ(back->position, s.position);
  EXPECT_EQ(back->normal, s.normal);
  EXPECT_EQ(back->albedo, s.albedo);
  EXPECT_EQ(back->vertex, s.vertex);
  ASSERT_TRUE(CheckStoreComplete(store).ok()) << CheckStoreComplete(store);

  // The manifest's sample count holds the arrays to it; a chunk gone is named.
  nlohmann::json attrs = Attrs();
  attrs["S"] = 6;
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  EXPECT_EQ(ReadSamples(store).status().code(), absl::StatusCode::kDataLoss);
  attrs["S"] = 5;
  ASSERT_TRUE(WriteAttrs(store, attrs).ok());
  ASSERT_TRUE(ReadSamples(store).ok());
  const std::filesystem::path chunk = store::Path(store, store::kNormal) / "0.0";
  ASSERT_TRUE(std::filesystem::remove(chunk));
  const absl::Status missing = ReadSamples(store).status();
  EXPECT_EQ(missing.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(missing.message(), HasSubstr(chunk.string()));
  EXPECT_EQ(CheckStoreComplete(store).code(), absl::StatusCode::kDataLoss);
}

// VerifyStore (storage/store/store_verify.h) reads every chunk of every array: a
// whole store verifies; one flipped byte in any chunk is DATA_LOSS naming it.
TEST(StoreVerifyTest, EveryChunkIsRead) {
  TempDir dir;
  const auto store = dir.path() / "s.wbk";
  WriteStore(store);
  SampleSet samples;  // a finished store has its samples (VerifyStore reads them whole)
  samples.width = kW;
  samples.height = kH;
  samples.grid.assign(kW * kH, -1);
  samples.grid[0] = 0;
  samples.position = samples.normal = samples.albedo = {{0, 1, 0}};
  ASSERT_TRUE(WriteSamples(store, samples).ok());
  absl::StatusOr<int> arrays = VerifyStore(store);
  ASSERT_TRUE(arrays.ok()) << arrays.status();
  EXPECT_EQ(*arrays, 9);
  // The last chunk of the values: a reader that stopped early would miss it.
  const auto chunk = store / store::kData / "2";
  ASSERT_TRUE(std::filesystem::exists(chunk));
  std::vector<char> bytes(std::filesystem::file_size(chunk));
  std::ifstream(chunk, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(chunk, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  arrays = VerifyStore(store);
  EXPECT_EQ(arrays.status().code(), absl::StatusCode::kDataLoss) << arrays.status();
  EXPECT_THAT(arrays.status().message(), ::testing::HasSubstr("data/2"));
  // A chunk gone: Zarr would read the fill value; a finished store is DATA_LOSS.
  std::filesystem::remove(chunk);
  arrays = VerifyStore(store);
  EXPECT_EQ(arrays.status().code(), absl::StatusCode::kDataLoss) << arrays.status();
  EXPECT_THAT(arrays.status().message(), ::testing::HasSubstr("data/2: chunk [2] is missing"));
}

}  // namespace
}  // namespace wavebake
