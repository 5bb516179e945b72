// `wavebake view STORE… [--http ADDR]`: the stores relit on the browser's
// GPU from wavelet-tree textures (web/views/gpu_view.h). Loopback only: the view
// has no token.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "absl/strings/str_cat.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/process/coordinator_run.h"
#include "driver/process/signal_watcher.h"
#include "web/views/gpu_view.h"

namespace wavebake::cli {
namespace {

struct ViewFlags {
  std::vector<std::string> stores;
  std::string listen = "127.0.0.1:8765", address_file, probes;
  double cut_off = -1, target_error = -1;
  std::string bits = "auto";
  int jump_nodes = WaveletTreeOptions{}.jump_nodes;
};

void Run(const ViewFlags& f) {
  std::atomic<bool> stop{false};
  driver::SignalWatcher signals([&stop](int) { stop = true; });
  web::GpuViewOptions options;
  options.listen = f.listen;
  for (const std::string& s : f.stores) options.stores.emplace_back(s);
  absl::StatusOr<std::vector<int>> bits = ParseCodeBits(f.bits);
  if (!bits.ok()) Fail("view", "--" + std::string(bits.status().message()), kExitBadInput);
  options.trees.bits = *bits;
  options.trees.jump_nodes = f.jump_nodes;
  if (f.cut_off >= 0) options.trees.cut_off = f.cut_off;
  if (f.target_error >= 0) options.trees.target_error = f.target_error;
  if (!f.probes.empty()) {
    absl::StatusOr<web::ProbeCatalogue> probes = web::ProbeCatalogue::Scan(f.probes);
    if (!probes.ok()) Fail("view", probes.status());
    options.probes = *std::move(probes);
  }
  absl::StatusOr<std::unique_ptr<web::GpuViewServer>> server =
      web::GpuViewServer::Start(std::move(options));
  if (!server.ok()) Fail("view", server.status());
  if (!f.address_file.empty())
    if (absl::Status s = driver::WriteAddressFile(f.address_file, (*server)->address()); !s.ok())
      Fail("view", s);
  std::fprintf(stderr, "view: serving %sview?store=0; Ctrl-C to stop\n", (*server)->url().c_str());
  while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  (*server)->Stop();
}

}  // namespace

void AddViewCommand(CLI::App& app) {
  auto flags = std::make_shared<ViewFlags>();
  CLI::App* cmd = app.add_subcommand(
      "view", "serve a page that relights diffuse stores on the browser's GPU (WebGL2)");
  cmd->add_option("stores", flags->stores, "the stores (OUT.wbk)")->required();
  cmd->add_option("--http", flags->listen, "loopback host:port to serve on (port 0: any free)")
      ->capture_default_str();
  cmd->add_option("--http-address-file", flags->address_file,
                  "write the bound host:port here once listening");
  cmd->add_option("--probes", flags->probes, "directory of .hdr/.exr probes to offer");
  auto* cut = cmd->add_option("--cut-off", flags->cut_off, "as for export --format wavelet-tree")
                  ->check(CLI::NonNegativeNumber);
  auto* target =
      cmd->add_option("--target-error", flags->target_error,
                      "as for export (default " + absl::StrCat(kDefaultTreeTargetError) + ")")
          ->check(CLI::NonNegativeNumber);
  cut->excludes(target);
  cmd->add_option("--bits", flags->bits, "as for export: auto, B or one per level")
      ->capture_default_str();
  cmd->add_option("--jump-nodes", flags->jump_nodes, "as for export")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
