#pragma once
// The commands that read a finished store (DESIGN.md §5): `relight` and
// `eval`, one file each (cli/cmd_<name>.cc).
#include <CLI/CLI.hpp>

namespace wavebake::cli {

void AddRelightCommand(CLI::App& app);
void AddEvalCommand(CLI::App& app);

}  // namespace wavebake::cli
