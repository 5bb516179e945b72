#include "cli/stderr_log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace wavebake::cli {

void LogToStderr(spdlog::level::level_enum level) {
  std::shared_ptr<spdlog::logger> logger = spdlog::get("wavebake");
  if (!logger) logger = spdlog::stderr_color_mt("wavebake");
  spdlog::set_default_logger(logger);
  spdlog::set_level(level);
}

}  // namespace wavebake::cli
