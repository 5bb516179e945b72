#pragma once
// The BRDF flags `relight` and `eval` share (runtime/glossy_store.h).
#include <CLI/CLI.hpp>
#include <string>

#include "runtime/glossy_store.h"

namespace wavebake::cli {

struct GlossyFlags {
  GlossyOptions options;
  std::string view;
};

// --brdf, --brdf-terms, --view.
void AddGlossyFlags(CLI::App& cmd, GlossyFlags& f);
// As GlossyOptions; a bad --view fails `command`.
GlossyOptions GlossyOf(const GlossyFlags& f, const char* command);

}  // namespace wavebake::cli
