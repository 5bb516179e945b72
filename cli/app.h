#pragma once

namespace wavebake::cli {

// Parses argv, runs one command, returns the process exit status.
int Run(int argc, char** argv);

}  // namespace wavebake::cli
