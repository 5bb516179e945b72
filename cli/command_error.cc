#include "cli/command_error.h"

#include <CLI/CLI.hpp>
#include <cstdio>

namespace wavebake::cli {

void Fail(const std::string& command, const absl::Status& status) {
  const absl::StatusCode code = status.code();
  const bool bad_input =
      code == absl::StatusCode::kInvalidArgument || code == absl::StatusCode::kNotFound ||
      code == absl::StatusCode::kAlreadyExists || code == absl::StatusCode::kOutOfRange;
  Fail(command, status.ToString(), bad_input ? kExitBadInput : kExitFailure);
}

void Fail(const std::string& command, const std::string& message, int exit_status) {
  std::fprintf(stderr, "wavebake %s: %s\n", command.c_str(), message.c_str());
  std::fflush(stderr);
  throw CLI::RuntimeError(exit_status);
}

}  // namespace wavebake::cli
