#pragma once
// The commands of the bake service (DESIGN.md §5), one file each
// (cli/cmd_<name>.cc): the embedded `bake`, the `coordinator` and `worker`
// processes, and the clients of a running coordinator.
#include <CLI/CLI.hpp>

namespace wavebake::cli {

void AddBakeCommand(CLI::App& app);
void AddCoordinatorCommand(CLI::App& app);
void AddWorkerCommand(CLI::App& app);
void AddSubmitCommand(CLI::App& app);
void AddWatchCommand(CLI::App& app);
void AddStatusCommand(CLI::App& app);
void AddCancelCommand(CLI::App& app);
void AddFetchCommand(CLI::App& app);
void AddHealthCommand(CLI::App& app);

}  // namespace wavebake::cli
