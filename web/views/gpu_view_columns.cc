// mode=4d of `wavebake view` (web/views/gpu_view.h): the 4D store decoded on the
// GPU (4D paper §4.5, Eq. 8). The store's CSC arrays go to the page once,
// as they are in memory after decoding (DESIGN.md §3: positions in the W×H
// Mallat layout of each column's own depth, values dequantized); per
// probe, rotation and term count the server sends only the kept lights
// (column, RGB weight: 16 bytes each), the same SelectWaveletLights the
// CPU relighter and the tree mode use. The page scatters each depth
// group's coefficients with additive float blending and inverts one Haar
// step between groups (web/static/view_4d.js).
#include <bit>
#include <chrono>
#include <cstring>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/wavelets/wavelet2d.h"
#include "runtime/gpu/relight_magnitude.h"
#include "runtime/gpu/wavelet_tree.h"
#include "runtime/relight/row_basis.h"
#include "web/views/gpu_view_state.h"

namespace wavebake::web {
namespace {

template <typename T>
std::string BytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

const char* FilterName(WaveletFilter f) {
  switch (f) {
    case WaveletFilter::kHaar:
      return "haar";
    case WaveletFilter::kDaub4:
      return "daub4";
    case WaveletFilter::kLeGall53:
      return "legall53";
    case WaveletFilter::kCdf97:
      return "cdf97";
  }
  return "?";
}

}  // namespace

absl::StatusOr<ServedColumns> ServeColumns(const CompressedColumns& t, const SampleSet& samples,
                                           bool oracle) {
  if (t.column_filter != WaveletFilter::kHaar)
    return absl::FailedPreconditionError(
        absl::StrCat("store: column_filter is ", FilterName(t.column_filter),
                     "; mode=4d inverts Haar column steps only (bake with --column-filter haar)"));
  const int64_t nnz = static_cast<int64_t>(t.indices.size());
  if (nnz >= (int64_t{1} << 31))
    return absl::FailedPreconditionError(
        absl::StrCat("transport: ", nnz, " coefficients do not fit 32-bit texel indices"));
  absl::StatusOr<Relighter> r = Relighter::Create(t, samples);  // its checks, always
  if (!r.ok()) return r.status();
  ServedColumns s;
  if (oracle) {
    s.columns = t;
    s.relighter = std::make_unique<Relighter>(*std::move(r));
  }
  // Entries: RG32UI, position then the value's float bits, kTreeLineWidth a row.
  const int64_t rows = std::max<int64_t>(1, WaveletTreeTextures::RowsFor(nnz));
  std::vector<uint32_t> entries(2 * rows * kTreeLineWidth, 0u);
  for (int64_t k = 0; k < nnz; ++k) {
    entries[2 * k] = t.indices[k];
    entries[2 * k + 1] = std::bit_cast<uint32_t>(t.values[k]);
  }
  std::vector<uint32_t> indptr(t.indptr.begin(), t.indptr.end());
  std::vector<float> cells(4 * size_t(t.width) * t.height, 0.0f);
  for (size_t c = 0; c < samples.grid.size(); ++c) {
    const int32_t id = samples.grid[c];
    if (id < 0) continue;
    const Vec3 a = samples.albedo[id];
    cells[4 * c] = a.x;
    cells[4 * c + 1] = a.y;
    cells[4 * c + 2] = a.z;
    cells[4 * c + 3] = 1.0f;
  }
  s.cells = BytesOf(cells);
  s.light_res = t.light_res;
  s.support = SupportSolidAngles(t.light_res);
  s.entries = BytesOf(entries);
  s.indptr = BytesOf(indptr);
  s.depth = BytesOf(t.depth);
  s.meta = {
      {"format", "wavebake-columns/1"},
      {"width", t.width},
      {"height", t.height},
      {"light_res", t.light_res},
      {"columns", t.columns},
      {"nonzeros", nnz},
      {"column_filter", FilterName(t.column_filter)},
      {"max_depth", MaxDepth(t.width, t.height)},
      {"entries",
       {{"file", "entries.bin"},
        {"texels", nnz},
        {"width", kTreeLineWidth},
        {"height", rows},
        {"type", "uint32"},
        {"channels", 2},
        {"webgl", "RG32UI / RG_INTEGER / UNSIGNED_INT"},
        {"meaning",
         "texel k (at (k mod width, k div width)) = entry k of the CSC matrix: R the position "
         "y*W + x in its column's Mallat layout, G the float32 bits of the dequantized value"}}},
      {"indptr",
       {{"file", "indptr.bin"},
        {"type", "uint32"},
        {"shape", {t.columns + 1}},
        {"meaning", "column m's entries are [indptr[m], indptr[m+1])"}}},
      {"depth",
       {{"file", "depth.bin"},
        {"type", "uint8"},
        {"shape", {t.columns}},
        {"meaning", "column m's transform depth: Haar steps 0..depth-1 were applied"}}},
      {"cells",
       {{"file", "cells.bin"},
        {"type", "float32"},
        {"channels", 4},
        {"shape", {t.height, t.width}},
        {"webgl", "RGBA32F / RGBA / FLOAT"},
        {"meaning", "cell y*W + x: albedo RGB, A 1 sampled / 0 masked"}}},
      {"bytes", s.entries.size() + s.indptr.size() + s.depth.size()}};
  return s;
}

namespace {

// Σ nonzeros of the lights' columns: the coefficients one frame scatters.
int64_t Scattered(const CompressedColumns& t, const WaveletLights& lights) {
  int64_t n = 0;
  for (const WaveletLight& l : lights.lights) n += t.indptr[l.column + 1] - t.indptr[l.column];
  return n;
}

}  // namespace

std::string LightsBody(const WaveletLights& lights) {
  std::string body(16 * lights.lights.size(), '\0');
  for (size_t k = 0; k < lights.lights.size(); ++k) {
    const WaveletLight& l = lights.lights[k];
    std::memcpy(&body[16 * k], &l.column, 4);
    std::memcpy(&body[16 * k + 4], l.weight.data(), 12);
  }
  return body;
}

void AddColumnArrayRoutes(httplib::Server& server, const std::string& prefix, ColumnsOf of) {
  server.Get(prefix + R"((meta\.json|entries\.bin|indptr\.bin|depth\.bin|cells\.bin))",
             [of](const httplib::Request& req, httplib::Response& res) {
               std::shared_ptr<const ServedColumns> c = of(req, res);
               if (!c) return;
               const std::string file = req.matches[2].str();
               if (file == "meta.json") return SendJsonBody(res, c->meta);
               SendBytes(res, file == "entries.bin"  ? c->entries
                              : file == "indptr.bin" ? c->indptr
                              : file == "depth.bin"  ? c->depth
                                                     : c->cells);
             });
}

void AddColumnRoutes(httplib::Server& server, GpuViewState& st) {
  AddColumnArrayRoutes(server, "/api/view/columns/(\\d+)/",
                       [&st](const httplib::Request& req,
                             httplib::Response& res) -> std::shared_ptr<const ServedColumns> {
                         size_t i = 0;
                         if (!absl::SimpleAtoi(req.matches[1].str(), &i) || i >= st.stores.size()) {
                           SendStatus(res, absl::NotFoundError("store: no such index"));
                           return nullptr;
                         }
                         if (!st.stores[i].cols_status.ok()) {
                           SendStatus(res, st.stores[i].cols_status);
                           return nullptr;
                         }
                         // Aliasing: the stores outlive the server's routes.
                         return std::shared_ptr<const ServedColumns>(std::shared_ptr<void>(),
                                                                     &st.stores[i].cols);
                       });
  // The kept lights, most important first: per light uint32 column, then
  // float32 R, G, B (little-endian, 16 bytes).
  server.Get("/api/view/lights", [&st](const httplib::Request& req, httplib::Response& res) {
    absl::StatusOr<FrameQuery> q = ParseFrameQuery(req, st.stores);
    if (!q.ok()) return SendStatus(res, q.status());
    if (!q->store->cols_status.ok()) return SendStatus(res, q->store->cols_status);
    absl::StatusOr<WaveletLights> lights = st.Lights(*q->store, q->probe, q->rotate, q->terms);
    if (!lights.ok()) return SendStatus(res, lights.status());
    res.set_header("X-Coefficients", std::to_string(Scattered(q->store->cols.columns, *lights)));
    SendBytes(res, LightsBody(*lights));
  });
  // The CPU relighter's frame of the same lights (Relighter::Relight, Eq. 8),
  // float32 [H·W·3] then M·|albedo| [H·W·3] (runtime/gpu/relight_magnitude.h,
  // the size that bounds the float rounding), row 0 at the top, NaN masked.
  // X-Frame-Ms: the relighter's time for the frame, the lights already chosen.
  server.Get("/api/view/oracle4d", [&st](const httplib::Request& req, httplib::Response& res) {
    absl::StatusOr<FrameQuery> q = ParseFrameQuery(req, st.stores);
    if (!q.ok()) return SendStatus(res, q.status());
    if (!q->store->cols_status.ok()) return SendStatus(res, q->store->cols_status);
    const ServedColumns& c = q->store->cols;
    absl::StatusOr<WaveletLights> lights = st.Lights(*q->store, q->probe, q->rotate, q->terms);
    if (!lights.ok()) return SendStatus(res, lights.status());
    absl::StatusOr<std::vector<float>> magnitude = RelightMagnitude(c.columns, lights->lights);
    if (!magnitude.ok()) return SendStatus(res, magnitude.status());
    std::vector<float> frame(magnitude->size());
    double ms = 0;
    {
      std::lock_guard lock(*c.mu);
      const auto start = std::chrono::steady_clock::now();
      c.relighter->Relight(*lights, frame);
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
               .count();
      c.relighter->ApplyAlbedo(*magnitude, *magnitude);
    }
    for (float& m : *magnitude) m = std::fabs(m);
    std::string body = BytesOf(frame) + BytesOf(*magnitude);
    res.set_header("X-Frame-Ms", absl::StrCat(ms));
    res.set_header("X-Coefficients", std::to_string(Scattered(c.columns, *lights)));
    SendBytes(res, std::move(body));
  });
}

}  // namespace wavebake::web
