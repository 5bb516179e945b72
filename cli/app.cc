#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "cli/command_error.h"
#include "cli/commands.h"

namespace wavebake::cli {

int Run(int argc, char** argv) {
  // Logs go to stderr, so that stdout carries only results (a job id, a
  // status table) for scripts; warnings only, but for the coordinator and
  // worker, whose log is their output.
  spdlog::set_default_logger(spdlog::stderr_color_mt("wavebake"));
  spdlog::set_level(spdlog::level::warn);
  CLI::App app{"wavebake: bake, compress and relight all-frequency light transport"};
  app.require_subcommand(1);
  // The version of the build (CMakeLists.txt's project(), the package's too).
  app.set_version_flag("--version", WB_VERSION, "print the version (" WB_VERSION ") and exit");
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
  AddExportCommand(app);
  AddViewCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help is success; a flag the parser refused is bad input like any other.
    const int status = app.exit(e);
    return status == 0 || dynamic_cast<const CLI::RuntimeError*>(&e) ? status : kExitBadInput;
  }
  return 0;
}

}  // namespace wavebake::cli
