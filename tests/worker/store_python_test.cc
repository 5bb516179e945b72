// The independent reader (DESIGN.md §3): /usr/bin/python3 with zarr opens
// every array of a finished store, scipy reads the transport group as CSC,
// and numpy rebuilds every column's values from indptr/indices/data/scale/
// depth with its own dither (splitmix64 in uint64) and its own subband level
// formula — bit for bit equal to the C++ reader's float32 values.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_params_io.h"
#include "storage/store/store_reader.h"
#include "tests/worker/column_test_support.h"
#include "worker/columns/finalize.h"

namespace wavebake {
namespace {

using column_testing::MakeContext;
using column_testing::RunPython;
using column_testing::ScratchDir;
using column_testing::SyntheticMatrix;
using column_testing::TransformAll;
using column_testing::WriteSyntheticStaging;

constexpr char kCheckStore[] = R"PY(
import numpy as np, numcodecs, scipy.sparse, zarr
root = zarr.open('out.wbk', mode='r')
a = root.attrs.asdict()
assert a['format'] == 'wavebake/2', a['format']
assert a['level_scaling'] == a['params']['level_scaling'] == SCALING, a['level_scaling']
W, H, N, M, bits, seed = a['W'], a['H'], a['N'], a['M'], a['bits'], a['params']['seed']
S = a['S']
assert M == 6 * N * N
expected = {'transport/indptr': ('<i8', (M + 1,)), 'transport/indices': ('<u4', None),
            'transport/data': ('<i2', None), 'transport/depth': ('|u1', (M,)),
            'transport/scale': ('<f4', (M,)), 'samples/grid': ('<i4', (H, W)),
            'samples/position': ('<f4', (S, 3)), 'samples/normal': ('<f4', (S, 3)),
            'samples/albedo': ('<f4', (S, 3))}
found = []
root.visititems(lambda name, obj: found.append(name) if isinstance(obj, zarr.Array) else None)
assert sorted(found) == sorted(expected), found
arrays = {}
for name, (dtype, shape) in expected.items():
    z = root[name]
    assert isinstance(z.compressor, numcodecs.Zstd), (name, z.compressor)
    assert z.dtype == np.dtype(dtype), (name, z.dtype)
    if shape is not None:
        assert z.shape == shape, (name, z.shape, shape)
    arrays[name] = z[...]
assert [f.codec_id for f in root['transport/indices'].filters] == ['delta', 'shuffle']
t = root['transport']
assert t.attrs['encoding-type'] == 'csc_matrix' and t.attrs['encoding-version'] == '0.1.0'
assert list(t.attrs['shape']) == [W * H, M]
indptr, indices = arrays['transport/indptr'], arrays['transport/indices']
data, depth, scale = arrays['transport/data'], arrays['transport/depth'], arrays['transport/scale']
assert indptr[0] == 0 and indptr[-1] == indices.size == data.size and np.all(np.diff(indptr) >= 0)
csc = scipy.sparse.csc_matrix((data, indices, indptr), shape=(W * H, M))
assert csc.nnz == data.size
grid = arrays['samples/grid']
assert grid.max() == S - 1 and grid.min() >= -1

def mix(z):
    z = z + np.uint64(0x9E3779B97F4A7C15)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))

def dither(column, positions):
    h = mix(mix(mix(np.uint64(seed)) ^ np.uint64(column)) ^ positions.astype(np.uint64))
    return ((h >> np.uint64(40)).astype(np.float64) * 2.0**-24 - 0.5).astype(np.float32)

# Square grid: the details of step s fill max(x, y) in [W >> (s+1), W >> s),
# so their level d-1-s is bit_length(max(x, y)) - (log2 W - d) - 1; the LL
# block and the last step's details are level 0.
assert W == H
log2w = W.bit_length() - 1
def levels(positions, d):
    if d == 0:
        return np.zeros(positions.size, dtype=np.int64)
    m = np.maximum(positions % W, positions // W).astype(np.int64)
    bl = np.zeros_like(m)
    nz = m > 0
    bl[nz] = np.floor(np.log2(m[nz])).astype(np.int64) + 1
    return np.maximum(0, bl - (log2w - d) - 1)

s = 1 if a['level_scaling'] == 'paper' else 0
ours = np.fromfile('values.f32', dtype='<f4')
assert ours.size == data.size, (ours.size, data.size)
with np.errstate(over='ignore'):
    for m in range(M):
        b, e = indptr[m], indptr[m + 1]
        pos = indices[b:e]
        u = dither(m, pos).astype(np.float64)
        l = levels(pos, int(depth[m]))
        v = (data[b:e].astype(np.float64) - u) * np.float64(scale[m]) * 2.0 ** (-s * l)
        v = v.astype(np.float32) if scale[m] != 0 else np.zeros(e - b, np.float32)
        bad = np.flatnonzero(v.view('<u4') != ours[b:e].view('<u4'))
        assert bad.size == 0, ('column', m, 'first bad', bad[:1], v[bad[:1]], ours[b:e][bad[:1]])
print('python rebuilt', M, 'columns,', data.size, 'values bit-exact')
)PY";

class StorePythonTest : public ::testing::TestWithParam<LevelScaling> {};

TEST_P(StorePythonTest, ZarrOpensEveryArrayAndNumpyRebuildsEveryColumnBitExact) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  BakeParams p;
  p.light_res = 8;
  p.supersample = 1;
  p.tile_size = 16;
  p.column_group = 100;
  p.seed = 0xDEADBEEFCAFEull;  // high bits set: the uint64 arithmetic must wrap alike
  p.level_scaling = GetParam();
  auto ctx = MakeContext(p);
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(32, 32));
  TransformAll(*ctx, store);
  ASSERT_TRUE(Finalize(*ctx, store, {}).ok());

  absl::StatusOr<CompressedColumns> t = ReadTransport(store);
  ASSERT_TRUE(t.ok()) << t.status();
  {
    std::ofstream out(dir.path() / "values.f32", std::ios::binary);
    out.write(reinterpret_cast<const char*>(t->values.data()),
              static_cast<std::streamsize>(t->values.size() * sizeof(float)));
  }
  const std::string script =
      absl::StrCat("SCALING = '", std::string(ToString(GetParam())), "'\n", kCheckStore);
  const column_testing::ProcessResult r = RunPython(dir.path(), script);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("python rebuilt 384 columns")) << r.output;
  std::cout << r.output;
}

INSTANTIATE_TEST_SUITE_P(Scalings, StorePythonTest,
                         ::testing::Values(LevelScaling::kUniform, LevelScaling::kPaper));

}  // namespace
}  // namespace wavebake
