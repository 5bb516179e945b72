#pragma once
// `wavebake view STORE…`: relighting on the user's GPU, in two modes.
// mode=tree (Boulton §4.5): the server turns each diffuse store into
// wavelet-tree textures once (driver/relight/tree_export.h) and serves their bytes
// as exported; per probe, rotation and term count it sends the environment
// trees (runtime/gpu/env_trees.h, a few KB: the lighting projection stays
// on the server, like the relight view's), and the page's fragment shader
// (web/static/wavelet_tree.frag) computes every texel. mode=4d (4D paper
// §4.5, web/views/gpu_view_columns.cc): the store's own arrays once, then only
// the kept lights; the page scatters and inverse-transforms them. No
// pixels travel. uv stores also get their mesh for a 3D display.
//
//   /view?store=I&probe=NAME&rotate=DEG&terms=K&mode=tree|4d   the page
//   /api/view/stores                                        the stores
//   /api/view/trees/I/FILE                                  header.json and arrays
//   /api/view/env?store=I&probe=&rotate=&terms=             environment trees
//   /api/view/oracle?store=I&probe=&rotate=&terms=          the CPU decoder's frame
//   /api/view/columns/I/FILE, /api/view/lights, /api/view/oracle4d   mode=4d
//   /api/view/mesh/I                                        a uv store's mesh
//
// The oracle (runtime/gpu/wavelet_tree_reader.h, sharing no code with the
// shader or the exporter's walk) relights the same exported bytes under the
// same lights: float32 [H·W·3] frame then [H·W·3] Σ|terms| (the size of the
// sum, for float error bounds), row 0 at the top, NaN where masked.
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/gpu/wavelet_tree.h"
#include "web/views/probe_catalogue.h"

namespace httplib {
class Server;
}

namespace wavebake::web {

struct GpuViewState;

struct GpuViewOptions {
  std::string listen = "127.0.0.1:0";  // loopback only: the view has no token
  std::vector<std::filesystem::path> stores;
  ProbeCatalogue probes{};
  WaveletTreeOptions trees{};
  std::filesystem::path pages_dir{};  // as MonitorOptions::pages_dir
};

class GpuViewServer {
 public:
  // Exports every store (errors name the store), binds (errors name
  // `listen`; a host other than loopback is refused), serves on a thread.
  static absl::StatusOr<std::unique_ptr<GpuViewServer>> Start(GpuViewOptions options);
  ~GpuViewServer();
  std::string url() const;  // http://host:port/
  std::string address() const;
  void Stop();

 private:
  GpuViewServer();
  std::unique_ptr<GpuViewState> state_;
  std::unique_ptr<httplib::Server> server_;
  std::string host_;
  int port_ = 0;
  std::thread thread_;
};

}  // namespace wavebake::web
