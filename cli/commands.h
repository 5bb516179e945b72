#pragma once
// The subcommands of `wavebake` (DESIGN.md §5) in cli/cmd_*.cc: the embedded
// `bake`; the `coordinator` and `worker` processes; `submit`, `status` and the
// one-shot clients of a running coordinator (cmd_job_clients.cc); the readers
// of a finished store, `relight` and `eval`.
#include <CLI/CLI.hpp>

namespace wavebake::cli {

// Parses argv, runs one command, returns the process exit status (cli/app.cc).
int Run(int argc, char** argv);

void AddBakeCommand(CLI::App& app);
void AddCoordinatorCommand(CLI::App& app);
void AddWorkerCommand(CLI::App& app);
void AddSubmitCommand(CLI::App& app);
void AddWatchCommand(CLI::App& app);
void AddStatusCommand(CLI::App& app);
void AddCancelCommand(CLI::App& app);
void AddFetchCommand(CLI::App& app);
void AddHealthCommand(CLI::App& app);
void AddRelightCommand(CLI::App& app);
void AddEvalCommand(CLI::App& app);
void AddExportCommand(CLI::App& app);
void AddViewCommand(CLI::App& app);

}  // namespace wavebake::cli
