#include "web/views/gpu_view.h"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "driver/relight/tree_export.h"
#include "runtime/env/env_map.h"
#include "runtime/gpu/env_trees.h"
#include "runtime/gpu/wavelet_tree_reader.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/row_basis.h"
#include "runtime/relight/store_relight.h"
#include "storage/store/store_reader.h"
#include "web/pages.h"
#include "web/views/gpu_view_state.h"

namespace wavebake::web {

void SendJsonBody(httplib::Response& res, const nlohmann::json& j, int status) {
  res.status = status;
  res.set_header("Cache-Control", "no-cache");
  res.set_content(j.dump(), "application/json");
}

void SendStatus(httplib::Response& res, const absl::Status& s) {
  int code = 500;
  switch (s.code()) {
    case absl::StatusCode::kInvalidArgument:
      code = 400;
      break;
    case absl::StatusCode::kNotFound:
      code = 404;
      break;
    case absl::StatusCode::kFailedPrecondition:
      code = 409;
      break;
    default:
      break;
  }
  SendJsonBody(res, {{"error", std::string(s.message())}}, code);
}

void SendBytes(httplib::Response& res, std::string body) {
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::move(body), "application/octet-stream");
}

absl::StatusOr<FrameQuery> ParseFrameQuery(const httplib::Request& req,
                                           const std::vector<ServedStore>& stores) {
  FrameQuery q;
  int index = 0;
  if (req.has_param("store") && !absl::SimpleAtoi(req.get_param_value("store"), &index))
    return absl::InvalidArgumentError("store: not an index");
  if (index < 0 || index >= static_cast<int>(stores.size()))
    return absl::NotFoundError(absl::StrCat("store: no store ", index));
  q.store = &stores[index];
  if (req.has_param("probe")) q.probe = req.get_param_value("probe");
  if (req.has_param("rotate") && !absl::SimpleAtod(req.get_param_value("rotate"), &q.rotate))
    return absl::InvalidArgumentError("rotate: not a number");
  if (req.has_param("terms") && !absl::SimpleAtoi(req.get_param_value("terms"), &q.terms))
    return absl::InvalidArgumentError("terms: not an integer");
  return q;
}

namespace {

std::string Bytes(const void* p, size_t n) { return std::string(static_cast<const char*>(p), n); }

absl::StatusOr<ServedStore> Serve(const std::filesystem::path& path,
                                  const WaveletTreeOptions& options) {
  auto named = [&path](const absl::Status& s) {
    return absl::Status(s.code(), absl::StrCat(path.string(), ": ", s.message()));
  };
  absl::StatusOr<driver::TreeSource> source = driver::OpenTreeSource(path);
  if (!source.ok()) return named(source.status());
  absl::StatusOr<WaveletTreeTextures> t = driver::WaveletTreesOf(*source, options);
  if (!t.ok()) return named(t.status());
  ServedStore s;
  s.name = path.filename().string();
  if (s.name.empty()) s.name = path.parent_path().filename().string();
  s.width = t->width;
  s.height = t->height;
  s.light_res = t->light_res;
  s.code_bits = t->code_bits;
  s.header = WaveletTreeHeader(*t, {{"store", s.name}});
  s.line = Bytes(t->line.data(), t->line.size());
  s.blocks = Bytes(t->blocks.data(), t->blocks.size() * 4);
  s.cells = Bytes(t->cells.data(), t->cells.size() * 4);
  auto vec = [](const std::string& b) { return std::vector<uint8_t>(b.begin(), b.end()); };
  absl::StatusOr<WaveletTreeReader> r =
      WaveletTreeReader::Parse(s.header, vec(s.line), vec(s.blocks), vec(s.cells));
  if (!r.ok()) return r.status();
  s.reader = std::make_unique<WaveletTreeReader>(*std::move(r));
  s.support = SupportSolidAngles(s.light_res);
  // A store mode=4d cannot relight (a column filter other than Haar) is
  // still served as trees; its 4d routes answer with the reason.
  absl::StatusOr<ServedColumns> cols = ServeColumns(source->columns, source->samples, true);
  if (cols.ok())
    s.cols = *std::move(cols);
  else
    s.cols_status = named(cols.status());
  if (absl::StatusOr<StoreInfo> info = ReadStoreInfo(path); info.ok()) {
    absl::StatusOr<LightmapMesh> mesh = LightmapMeshOf(*info, source->samples);
    if (mesh.ok()) {
      const uint32_t counts[2] = {static_cast<uint32_t>(mesh->positions.size() / 3),
                                  static_cast<uint32_t>(mesh->indices.size())};
      s.mesh = Bytes(counts, sizeof counts) +
               Bytes(mesh->positions.data(), 4 * mesh->positions.size()) +
               Bytes(mesh->texels.data(), 4 * mesh->texels.size()) +
               Bytes(mesh->indices.data(), 4 * mesh->indices.size());
    } else if (mesh.status().code() != absl::StatusCode::kFailedPrecondition ||
               info->params.layout.starts_with("uv")) {
      spdlog::warn("view: {}: no 3D mesh ({}); the lightmap is shown flat", path.string(),
                   std::string(mesh.status().message()));
    }
  }
  return s;
}

bool IsLoopback(const std::string& host) {
  return host == "127.0.0.1" || host == "localhost" || host == "::1";
}

void AddRoutes(httplib::Server& server, GpuViewState& st) {
  auto page = [&st](const std::string& name, httplib::Response& res) {
    std::optional<std::string> body = st.pages.Get(name);
    if (!body) {
      res.status = 404;
      res.set_content("not found\n", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-cache");
    res.set_header("Content-Security-Policy", "default-src 'self'; style-src 'self'");
    const bool shader = name.ends_with(".frag") || name.ends_with(".vert");
    res.set_content(*body, shader ? "text/plain; charset=utf-8" : Pages::ContentType(name));
  };
  server.Get(
      "/", [](const httplib::Request&, httplib::Response& res) { res.set_redirect("/view", 303); });
  server.Get("/view",
             [page](const httplib::Request&, httplib::Response& res) { page("view.html", res); });
  server.Get(R"(/static/([A-Za-z0-9_.-]+))",
             [page](const httplib::Request& req, httplib::Response& res) {
               page(req.matches[1].str(), res);
             });
  server.Get("/api/probes", [&st](const httplib::Request&, httplib::Response& res) {
    SendJsonBody(res, st.lights->probes().names());
  });
  server.Get("/api/view/stores", [&st](const httplib::Request&, httplib::Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (size_t i = 0; i < st.stores.size(); ++i) {
      const ServedStore& s = st.stores[i];
      list.push_back({{"index", i},
                      {"name", s.name},
                      {"width", s.width},
                      {"height", s.height},
                      {"light_res", s.light_res},
                      {"code_bits", s.code_bits},
                      {"mesh", !s.mesh.empty()},
                      {"bytes", s.line.size() + s.blocks.size() + s.cells.size()}});
    }
    SendJsonBody(res, list);
  });
  server.Get(R"(/api/view/trees/(\d+)/(header\.json|line\.bin|blocks\.bin|cells\.bin))",
             [&st](const httplib::Request& req, httplib::Response& res) {
               size_t i = 0;
               if (!absl::SimpleAtoi(req.matches[1].str(), &i) || i >= st.stores.size())
                 return SendStatus(res, absl::NotFoundError("store: no such index"));
               const ServedStore& s = st.stores[i];
               const std::string file = req.matches[2].str();
               if (file == "header.json") return SendJsonBody(res, s.header);
               const std::string& body = file == "line.bin"     ? s.line
                                         : file == "blocks.bin" ? s.blocks
                                                                : s.cells;
               res.set_header("Cache-Control", "no-cache");
               res.set_content(body, "application/octet-stream");
             });
  server.Get(R"(/api/view/mesh/(\d+))", [&st](const httplib::Request& req, httplib::Response& res) {
    size_t i = 0;
    if (!absl::SimpleAtoi(req.matches[1].str(), &i) || i >= st.stores.size() ||
        st.stores[i].mesh.empty())
      return SendStatus(res, absl::NotFoundError("store: no mesh for this index"));
    SendBytes(res, st.stores[i].mesh);
  });
  server.Get("/api/view/env", [&st](const httplib::Request& req, httplib::Response& res) {
    absl::StatusOr<FrameQuery> q = ParseFrameQuery(req, st.stores);
    if (!q.ok()) return SendStatus(res, q.status());
    absl::StatusOr<WaveletLights> lights = st.Lights(*q->store, q->probe, q->rotate, q->terms);
    if (!lights.ok()) return SendStatus(res, lights.status());
    SendJsonBody(res, EnvTreesJson(BuildEnvTrees(*lights)));
  });
  server.Get("/api/view/oracle", [&st](const httplib::Request& req, httplib::Response& res) {
    absl::StatusOr<FrameQuery> q = ParseFrameQuery(req, st.stores);
    if (!q.ok()) return SendStatus(res, q.status());
    const ServedStore& s = *q->store;
    absl::StatusOr<WaveletLights> lights = st.Lights(s, q->probe, q->rotate, q->terms);
    if (!lights.ok()) return SendStatus(res, lights.status());
    std::vector<float> dense(3 * 6 * size_t(s.light_res) * s.light_res, 0.0f);
    for (const WaveletLight& l : lights->lights)
      for (int c = 0; c < 3; ++c) dense[3 * size_t(l.column) + c] = l.weight[c];
    std::vector<float> magnitude;
    absl::StatusOr<std::vector<float>> frame = s.reader->Relight(dense, &magnitude);
    if (!frame.ok()) return SendStatus(res, frame.status());
    std::string body(8 * frame->size(), '\0');
    std::memcpy(body.data(), frame->data(), 4 * frame->size());
    std::memcpy(body.data() + 4 * frame->size(), magnitude.data(), 4 * magnitude.size());
    res.set_header("Cache-Control", "no-cache");
    res.set_content(body, "application/octet-stream");
  });
}

}  // namespace

GpuViewServer::GpuViewServer() = default;
GpuViewServer::~GpuViewServer() { Stop(); }

absl::StatusOr<std::unique_ptr<GpuViewServer>> GpuViewServer::Start(GpuViewOptions options) {
  const size_t colon = options.listen.rfind(':');
  int port = -1;
  if (colon == std::string::npos || !absl::SimpleAtoi(options.listen.substr(colon + 1), &port) ||
      port < 0 || port > 65535)
    return absl::InvalidArgumentError(
        absl::StrCat("listen: \"", options.listen, "\" is not host:port (port 0: any free)"));
  std::string host = options.listen.substr(0, colon);
  if (host.size() > 2 && host.front() == '[') host = host.substr(1, host.size() - 2);
  if (!IsLoopback(host))
    return absl::InvalidArgumentError(absl::StrCat(
        "listen: ", host, " is not a loopback address; the view has no token to guard it"));
  if (options.stores.empty()) return absl::InvalidArgumentError("stores: none given");
  std::unique_ptr<GpuViewServer> v(new GpuViewServer());
  v->state_ = std::make_unique<GpuViewState>();
  v->state_->lights = std::make_unique<GpuLights>(std::move(options.probes));
  v->state_->pages = Pages(options.pages_dir);
  for (const auto& path : options.stores) {
    absl::StatusOr<ServedStore> s = Serve(path, options.trees);
    if (!s.ok()) return s.status();
    spdlog::info("view: {} as {}x{} trees, {} bytes", path.string(), s->width, s->height,
                 s->line.size() + s->blocks.size() + s->cells.size());
    v->state_->stores.push_back(*std::move(s));
  }
  v->server_ = std::make_unique<httplib::Server>();
  httplib::Server& server = *v->server_;
  server.new_task_queue = [] { return new httplib::ThreadPool(8); };
  server.set_payload_max_length(1 << 16);
  AddRoutes(server, *v->state_);
  AddColumnRoutes(server, *v->state_);
  v->host_ = host;
  v->port_ =
      port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (v->port_ <= 0)
    return absl::UnavailableError(
        absl::StrCat("listen: cannot listen on \"", options.listen, "\""));
  v->thread_ = std::thread([&server] { server.listen_after_bind(); });
  return v;
}

std::string GpuViewServer::address() const {
  return absl::StrCat(host_.find(':') != std::string::npos ? "[" + host_ + "]" : host_, ":", port_);
}
std::string GpuViewServer::url() const { return absl::StrCat("http://", address(), "/"); }

void GpuViewServer::Stop() {
  if (!server_) return;
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace wavebake::web
