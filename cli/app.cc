#include "cli/app.h"

#include <CLI/CLI.hpp>

#include "cli/cluster_commands.h"
#include "cli/runtime_commands.h"

namespace wavebake::cli {

int Run(int argc, char** argv) {
  CLI::App app{"wavebake: bake, compress and relight all-frequency light transport"};
  app.require_subcommand(1);
  AddBakeCommand(app);
  AddCoordinatorCommand(app);
  AddWorkerCommand(app);
  AddSubmitCommand(app);
  AddWatchCommand(app);
  AddStatusCommand(app);
  AddCancelCommand(app);
  AddFetchCommand(app);
  AddHealthCommand(app);
  AddRelightCommand(app);
  AddEvalCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return 0;
}

}  // namespace wavebake::cli
