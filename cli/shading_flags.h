#pragma once
// The flags `relight` and `eval` share: the material (runtime/glossy/glossy_store.h)
// and the near-field lights (driver/relight/area_light_commands.h).
#include <CLI/CLI.hpp>
#include <string>

#include "driver/relight/area_light_commands.h"
#include "driver/relight/relight_command.h"

namespace wavebake::cli {

struct GlossyFlags {
  GlossyOptions options;
  std::string view;
};

// --brdf, --brdf-terms, --view.
void AddGlossyFlags(CLI::App& cmd, GlossyFlags& f);
// As GlossyOptions; a bad --view fails `command`.
GlossyOptions GlossyOf(const GlossyFlags& f, const char* command);

// --area-light (repeatable), --source-fraction, --target-fraction.
void AddAreaLightFlags(CLI::App& cmd, driver::AreaLightCommand& c);

}  // namespace wavebake::cli
