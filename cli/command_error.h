#pragma once
// How a command ends in failure (DESIGN.md §5: "Exit status is non-zero on
// any error, with a message that names the bad input"): the message goes to
// stderr as "wavebake <command>: <status>", and a CLI::RuntimeError carries
// the exit status out through CLI::App::exit, which prints nothing more.
#include <string>

#include "absl/status/status.h"

namespace wavebake::cli {

// Exit statuses of the cluster commands.
inline constexpr int kExitFailure = 1;        // an error, a job that FAILED or was CANCELLED
inline constexpr int kExitBadInput = 2;       // a flag, file or request the command refused
inline constexpr int kExitInterrupted = 130;  // SIGINT / SIGTERM ended the command early

// INVALID_ARGUMENT (and a few like it) exit with kExitBadInput, the rest with kExitFailure.
[[noreturn]] void Fail(const std::string& command, const absl::Status& status);
[[noreturn]] void Fail(const std::string& command, const std::string& message,
                       int exit_status = kExitFailure);

}  // namespace wavebake::cli
