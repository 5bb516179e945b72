#pragma once
// The bake flags of DESIGN.md §5, shared by `bake` and `submit`, one per row of
// the table of bake parameters (driver/bake/bake_words.h). Numbers bind
// straight to BakeParams; names are parsed by driver/bake/bake_words.h, so the
// command line, the RPC and the store refuse the same strings.
#include <CLI/CLI.hpp>

#include "driver/bake/bake_words.h"

namespace wavebake::cli {

struct BakeFlags {
  BakeParams params;     // the numeric flags
  BakeParamWords words;  // the named ones
};

void AddBakeFlags(CLI::App& cmd, BakeFlags& f);

}  // namespace wavebake::cli
