#pragma once
// The area-light flags `relight` and `eval` share (driver/area_light_commands.h).
#include <CLI/CLI.hpp>

#include "driver/area_light_commands.h"

namespace wavebake::cli {

// --area-light (repeatable), --source-fraction, --target-fraction.
void AddAreaLightFlags(CLI::App& cmd, driver::AreaLightCommand& c);

}  // namespace wavebake::cli
