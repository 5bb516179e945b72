// `wavebake fetch JOB --out DIR --coordinator ADDR` (DESIGN.md §4 ReadStore):
// copies a finished store from the coordinator, without its filesystem, and
// verifies every array before it appears at DIR.
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/store_fetch.h"

namespace wavebake::cli {
namespace {

struct FetchFlags {
  std::string job;
  std::string out;
  driver::ClientConfig client;
};

void Run(const FetchFlags& f) {
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client);
  if (!client.ok()) Fail("fetch", client.status());
  absl::StatusOr<driver::FetchSummary> summary = driver::FetchStore(*client, f.job, f.out);
  if (!summary.ok()) Fail("fetch", summary.status());
  std::printf("%s: %d files, %lld bytes, %d arrays verified\n", f.out.c_str(), summary->files,
              static_cast<long long>(summary->bytes), summary->arrays);
}

}  // namespace

void AddFetchCommand(CLI::App& app) {
  auto f = std::make_shared<FetchFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fetch", "copy a finished job's store from the coordinator to a local directory, verified");
  cmd->add_option("JOB", f->job, "job id")->required();
  cmd->add_option("--out", f->out, "directory to create (must not exist)")->required();
  AddClientFlags(*cmd, f->client);
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
