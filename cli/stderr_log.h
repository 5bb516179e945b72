#pragma once
// The cluster commands log with spdlog to stderr, so stdout carries only
// their results (a job id, a status table) for scripts.
#include <spdlog/spdlog.h>

namespace wavebake::cli {

void LogToStderr(spdlog::level::level_enum level);

}  // namespace wavebake::cli
