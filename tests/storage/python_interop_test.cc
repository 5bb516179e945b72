// The independent reader: /usr/bin/python3 with zarr 2.13 / numcodecs 0.11
// must read every array we write, and we must read what zarr writes
// (DESIGN.md §3). Values are compared bit for bit against raw dumps written
// with plain stdio, never against this layer's own output. No skipping: a
// missing python or zarr fails the test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "storage/zarr/zarr_array.h"
#include "tests/storage/array_values.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using testing::BitEqual;
using testing::RunPython;
using testing::TempDir;
using testing::TestValues;
using testing::WriteRawFile;

class PythonInteropTest : public ::testing::Test {
 protected:
  // Writes `values` as array `path` under the store, a raw dump beside the
  // store, and a manifest entry for the python check.
  template <class T>
  void AddArray(const std::string& path, ArraySpec spec, const std::vector<T>& values) {
    absl::StatusOr<ZarrArray> array = ZarrArray::Create(store() / path, spec);
    ASSERT_TRUE(array.ok()) << array.status();
    ASSERT_TRUE(array->WriteAll<T>(values).ok());
    AddExpectation<T>(path, spec, values);
  }
  template <class T>
  void AddExpectation(const std::string& path, const ArraySpec& spec,
                      const std::vector<T>& expected) {
    const std::string raw = "raw_" + std::to_string(manifest_["arrays"].size()) + ".bin";
    WriteRawFile(tmp_.path() / raw, std::as_bytes(std::span(expected)));
    manifest_["arrays"].push_back(
        {{"path", path},
         {"raw", raw},
         {"dtype", std::string(ZarrName(spec.dtype))},
         {"shape", spec.shape},
         {"chunks", spec.chunks},
         {"fill_value",
          std::isnan(spec.fill_value) ? nlohmann::json("NaN") : nlohmann::json(spec.fill_value)},
         {"delta", spec.delta_filter}});
  }
  std::filesystem::path store() const { return tmp_.path() / "out.wbk"; }
  void SaveManifest() { std::ofstream(tmp_.path() / "manifest.json") << manifest_.dump(2); }

  TempDir tmp_;
  nlohmann::json manifest_ = {{"arrays", nlohmann::json::array()}};
};

// Reads the store exactly as DESIGN.md §3 says a user would: zarr.open on the root.
constexpr char kReadStore[] = R"PY(
import json, math, numpy as np, numcodecs, scipy.sparse, zarr
m = json.load(open('manifest.json'))
root = zarr.open('out.wbk', mode='r')
assert isinstance(root, zarr.hierarchy.Group), type(root)
assert root.attrs.asdict() == m['root_attrs'], root.attrs.asdict()
assert root['transport'].attrs.asdict() == m['transport_attrs'], root['transport'].attrs.asdict()
for a in m['arrays']:
    z = root[a['path']]
    where = a['path']
    assert z.shape == tuple(a['shape']), (where, z.shape)
    assert z.chunks == tuple(a['chunks']), (where, z.chunks)
    assert z.dtype == np.dtype(a['dtype']), (where, z.dtype)
    assert isinstance(z.compressor, numcodecs.Zstd), (where, z.compressor)
    assert z.order == 'C'
    fill = a['fill_value']
    if fill == 'NaN':
        assert math.isnan(z.fill_value), (where, z.fill_value)
    else:
        assert z.fill_value == fill, (where, z.fill_value, fill)
    if a['delta']:
        assert [f.codec_id for f in z.filters] == ['delta'], (where, z.filters)
    else:
        assert z.filters is None, (where, z.filters)
    expected = np.fromfile(a['raw'], dtype=a['dtype']).reshape(a['shape'])
    got = z[...]
    bits = 'u%d' % got.dtype.itemsize  # bit-exact, NaN payloads included
    bad = np.flatnonzero(got.view(bits) != expected.view(bits))
    assert bad.size == 0, (where, bad.size, 'wrong elements, first at flat index', bad[:1],
                           got.flat[bad[:1]], 'expected', expected.flat[bad[:1]])
# The transport group follows the scipy CSC convention (DESIGN.md §3).
t = root['transport']
csc = scipy.sparse.csc_matrix((t['data'][:], t['indices'][:], t['indptr'][:]),
                              shape=tuple(t.attrs['shape']))
dense = np.fromfile('dense.bin', dtype='<i2').reshape(t.attrs['shape'])
assert np.array_equal(csc.toarray(), dense)
print('python read', len(m['arrays']), 'arrays')
)PY";

TEST_F(PythonInteropTest, ZarrReadsEveryArrayWeWrite) {
  ASSERT_TRUE(WriteGroup(store()).ok());
  const nlohmann::json root_attrs = {{"format", "wavebake/1"},
                                     {"N", 8},
                                     {"filters", {"haar", "haar"}},
                                     {"stats", {{"rel_rms", 0.0125}, {"nnz", 12345}}}};
  ASSERT_TRUE(WriteAttrs(store(), root_attrs).ok());
  manifest_["root_attrs"] = root_attrs;

  AddArray<uint8_t>("a/u1_1d", {.shape = {1000}, .chunks = {128}, .dtype = DType::kUint8},
                    TestValues<uint8_t>(1000, 1));
  AddArray<int16_t>(
      "a/i2_2d", {.shape = {37, 50}, .chunks = {8, 16}, .dtype = DType::kInt16, .fill_value = -3},
      TestValues<int16_t>(37 * 50, 2));
  AddArray<int32_t>("a/i4_3d", {.shape = {5, 7, 3}, .chunks = {2, 3, 2}, .dtype = DType::kInt32},
                    TestValues<int32_t>(5 * 7 * 3, 3));
  AddArray<uint32_t>("a/u4_delta",
                     {.shape = {1000},
                      .chunks = {300},
                      .dtype = DType::kUint32,
                      .zstd_level = 5,
                      .delta_filter = true},
                     TestValues<uint32_t>(1000, 4));
  AddArray<int64_t>("a/i8_2d_delta",
                    {.shape = {9, 11},
                     .chunks = {4, 4},
                     .dtype = DType::kInt64,
                     .fill_value = -1,
                     .delta_filter = true},
                    TestValues<int64_t>(9 * 11, 5));
  AddArray<float>("a/f4_3d",
                  {.shape = {4, 6, 5},
                   .chunks = {3, 4, 4},
                   .dtype = DType::kFloat32,
                   .fill_value = std::numeric_limits<double>::quiet_NaN()},
                  TestValues<float>(4 * 6 * 5, 6));
  AddArray<uint32_t>("a/empty", {.shape = {0}, .chunks = {64}, .dtype = DType::kUint32},
                     std::vector<uint32_t>{});

  // Only some chunks written: the rest must read as the fill value in zarr too.
  const ArraySpec sparse{
      .shape = {20, 13}, .chunks = {8, 8}, .dtype = DType::kFloat32, .fill_value = 0.5};
  absl::StatusOr<ZarrArray> partial = ZarrArray::Create(store() / "a/partial", sparse);
  ASSERT_TRUE(partial.ok());
  const std::vector<float> chunk = TestValues<float>(64, 7);
  ASSERT_TRUE(partial->WriteChunk<float>(std::vector<int64_t>{2, 1}, chunk).ok());
  std::vector<float> expected(20 * 13, 0.5f);
  for (int r = 16; r < 20; ++r) {
    for (int c = 8; c < 13; ++c) expected[r * 13 + c] = chunk[(r - 16) * 8 + (c - 8)];
  }
  AddExpectation<float>("a/partial", sparse, expected);

  // A small CSC matrix: rows = 6 spatial samples, columns = 5 lights.
  const int rows = 6, cols = 5;
  std::vector<int16_t> dense(rows * cols, 0);
  std::vector<int64_t> indptr = {0};
  std::vector<uint32_t> indices;
  std::vector<int16_t> data;
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < rows; ++r) {
      if ((r * 7 + c * 3) % 4 == 0) continue;
      dense[r * cols + c] = static_cast<int16_t>(100 * c - 37 * r);
      indices.push_back(r);
      data.push_back(dense[r * cols + c]);
    }
    indptr.push_back(static_cast<int64_t>(indices.size()));
  }
  WriteRawFile(tmp_.path() / "dense.bin", std::as_bytes(std::span(dense)));
  const auto t = store() / "transport";
  ASSERT_TRUE(WriteGroup(t).ok());
  const nlohmann::json t_attrs = {
      {"encoding-type", "csc_matrix"}, {"encoding-version", "0.1.0"}, {"shape", {rows, cols}}};
  ASSERT_TRUE(WriteAttrs(t, t_attrs).ok());
  manifest_["transport_attrs"] = t_attrs;
  const int64_t nnz = static_cast<int64_t>(data.size());
  AddArray<int64_t>("transport/indptr",
                    {.shape = {cols + 1}, .chunks = {4}, .dtype = DType::kInt64}, indptr);
  AddArray<uint32_t>("transport/indices",
                     {.shape = {nnz}, .chunks = {7}, .dtype = DType::kUint32, .delta_filter = true},
                     indices);
  AddArray<int16_t>("transport/data", {.shape = {nnz}, .chunks = {7}, .dtype = DType::kInt16},
                    data);

  SaveManifest();
  const testing::ProcessResult r = RunPython(tmp_.path(), kReadStore);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("python read 11 arrays")) << r.output;
}

// zarr writes arrays (zstd frames without checksum, delta filters, missing
// chunks, NaN fill, "." keys) and raw dumps; we must read the same bits.
constexpr char kWriteArrays[] = R"PY(
import json, os, numpy as np, numcodecs, zarr
rng = np.random.default_rng(42)
cases = [('u1', '|u1', (1000,), (128,), 0, False), ('i2', '<i2', (37, 50), (8, 16), -3, False),
         ('i4', '<i4', (5, 7, 3), (2, 3, 2), 0, True), ('u4', '<u4', (999,), (100,), 7, True),
         ('i8', '<i8', (9, 11), (4, 4), -1, True), ('f4', '<f4', (4, 6, 5), (3, 4, 4), 'NaN', False)]
out = []
for name, dtype, shape, chunks, fill, delta in cases:
    n = int(np.prod(shape))
    values = np.frombuffer(rng.bytes(n * np.dtype(dtype).itemsize), dtype=dtype).reshape(shape)
    filters = [numcodecs.Delta(dtype=dtype)] if delta else None
    z = zarr.open_array('py/' + name, mode='w', shape=shape, chunks=chunks, dtype=dtype,
                        compressor=numcodecs.Zstd(level=3), filters=filters,
                        fill_value=float('nan') if fill == 'NaN' else fill,
                        write_empty_chunks=False)
    # Leave the first chunk unwritten: it must read as the fill value.
    expected = values.copy()
    first = tuple(slice(0, c) for c in chunks)
    expected[first] = np.nan if fill == 'NaN' else fill
    z[...] = expected
    assert not os.path.exists('py/%s/%s' % (name, '.'.join('0' * len(shape))))
    expected.tofile('py_%s.bin' % name)
    out.append({'name': name, 'dtype': dtype, 'shape': shape})
json.dump(out, open('py_manifest.json', 'w'))
print('python wrote', len(out), 'arrays')
)PY";

template <class T>
void ExpectMatchesRaw(const std::filesystem::path& dir, const std::filesystem::path& raw) {
  absl::StatusOr<ZarrArray> array = ZarrArray::Open(dir);
  ASSERT_TRUE(array.ok()) << array.status();
  absl::StatusOr<std::vector<T>> got = array->ReadAll<T>();
  ASSERT_TRUE(got.ok()) << got.status();
  std::ifstream in(raw, std::ios::binary);
  std::vector<T> expected(std::filesystem::file_size(raw) / sizeof(T));
  in.read(reinterpret_cast<char*>(expected.data()), expected.size() * sizeof(T));
  EXPECT_TRUE(BitEqual<T>(*got, expected)) << dir;
}

TEST_F(PythonInteropTest, WeReadWhatZarrWrites) {
  const testing::ProcessResult r = RunPython(tmp_.path(), kWriteArrays);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_THAT(r.output, ::testing::HasSubstr("python wrote 6 arrays")) << r.output;
  const auto dir = [&](const char* name) { return tmp_.path() / "py" / name; };
  const auto raw = [&](const char* name) {
    return tmp_.path() / (std::string("py_") + name + ".bin");
  };
  ExpectMatchesRaw<uint8_t>(dir("u1"), raw("u1"));
  ExpectMatchesRaw<int16_t>(dir("i2"), raw("i2"));
  ExpectMatchesRaw<int32_t>(dir("i4"), raw("i4"));
  ExpectMatchesRaw<uint32_t>(dir("u4"), raw("u4"));
  ExpectMatchesRaw<int64_t>(dir("i8"), raw("i8"));
  ExpectMatchesRaw<float>(dir("f4"), raw("f4"));
  absl::StatusOr<ZarrArray> f4 = ZarrArray::Open(dir("f4"));
  ASSERT_TRUE(f4.ok());
  EXPECT_TRUE(std::isnan(f4->spec().fill_value));
  EXPECT_EQ(f4->spec().zstd_level, 3);
  EXPECT_TRUE(ZarrArray::Open(dir("u4"))->spec().delta_filter);
}

}  // namespace
}  // namespace wavebake
