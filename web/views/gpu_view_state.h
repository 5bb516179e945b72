#pragma once
// What `wavebake view` (web/views/gpu_view.h) holds per store and shares between
// its two modes' routes: the tree textures (web/views/gpu_view.cc) and the 4D
// store's arrays (web/views/gpu_view_columns.cc).
#include <httplib.h>

#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/columns/compressed_columns.h"
#include "runtime/env/env_map.h"
#include "runtime/gpu/wavelet_tree_reader.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"
#include "web/pages.h"
#include "web/views/gpu_lights.h"
#include "web/views/probe_catalogue.h"

namespace wavebake::web {

// mode=4d: the store's CSC arrays as served, and the CPU relighter of the
// same store (the oracle; one frame at a time, its scratch is not shared).
struct ServedColumns {
  CompressedColumns columns;  // with the oracle only
  nlohmann::json meta;
  std::string entries, indptr, depth;
  std::string cells;  // [W·H] × RGBA float32: albedo RGB, A 1 sampled / 0 masked
  int light_res = 0;
  std::vector<float> support;  // SupportSolidAngles(N)
  std::unique_ptr<Relighter> relighter;
  std::unique_ptr<std::mutex> mu = std::make_unique<std::mutex>();
};

// One store as served: the exported tree bytes and the oracle reading them
// (mode=tree), its columns (mode=4d).
struct ServedStore {
  std::string name;
  int width = 0, height = 0, light_res = 0;
  std::vector<int> code_bits;  // per level
  nlohmann::json header;
  std::string line, blocks, cells;
  std::unique_ptr<WaveletTreeReader> reader;
  std::vector<float> support;  // SupportSolidAngles(N)
  ServedColumns cols;
  absl::Status cols_status;  // why mode=4d cannot serve this store (trees still can)
  // uv stores whose scene loads: the lightmapped mesh for the 3D display,
  // uint32 vertices V, uint32 indices I, float32 positions [V·3], float32
  // lightmap texel positions [V·2] (x right, y down from grid row 0),
  // uint32 indices [I]; empty otherwise.
  std::string mesh;
};

struct GpuViewState {
  std::vector<ServedStore> stores;
  std::unique_ptr<GpuLights> lights;
  Pages pages;

  // The lights of a frame of store s.
  absl::StatusOr<WaveletLights> Lights(const ServedStore& s, const std::string& probe,
                                       double rotate, int terms) {
    return lights->Lights(probe, rotate, terms, s.light_res, s.support);
  }
};

// A frame's query: ?store=I&probe=NAME&rotate=DEG&terms=K.
struct FrameQuery {
  const ServedStore* store = nullptr;
  std::string probe = "builtin:sky";
  double rotate = 0;
  int terms = 256;
};
absl::StatusOr<FrameQuery> ParseFrameQuery(const httplib::Request& req,
                                           const std::vector<ServedStore>& stores);

void SendJsonBody(httplib::Response& res, const nlohmann::json& j, int status = 200);
// 400 / 404 / 409 / 500 by the status code, {"error": message}.
void SendStatus(httplib::Response& res, const absl::Status& s);
void SendBytes(httplib::Response& res, std::string body);

// mode=4d: the store's columns, and with `oracle` its CPU relighter and a
// copy of the matrix for the magnitude (the view's oracle4d; the job page
// needs neither). Errors name the field: a column filter the GPU cannot
// invert, a matrix too large for 32-bit texel indices, the matrix's checks.
absl::StatusOr<ServedColumns> ServeColumns(const CompressedColumns& columns,
                                           const SampleSet& samples, bool oracle);
// The kept lights, most important first: per light uint32 column, then
// float32 R, G, B (little-endian, 16 bytes).
std::string LightsBody(const WaveletLights& lights);
// The arrays' routes: prefix + {meta.json,entries.bin,indptr.bin,depth.bin,
// cells.bin}, `of` finding the store's columns by the request's first match
// (or sending the error).
using ColumnsOf = std::function<std::shared_ptr<const ServedColumns>(const httplib::Request&,
                                                                     httplib::Response&)>;
void AddColumnArrayRoutes(httplib::Server& server, const std::string& prefix, ColumnsOf of);
//   /api/view/columns/I/{meta.json,entries.bin,indptr.bin,depth.bin,cells.bin}
//   /api/view/lights?store=I&probe=&rotate=&terms=     the kept lights
//   /api/view/oracle4d?store=I&probe=&rotate=&terms=   the CPU relighter's frame
void AddColumnRoutes(httplib::Server& server, GpuViewState& st);

}  // namespace wavebake::web
