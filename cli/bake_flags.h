#pragma once
// The bake flags of DESIGN.md §5, shared by `bake` and `submit`. Numbers bind
// straight to BakeParams; names are parsed by core/bake/bake_param_words.h, so the
// command line, the RPC and the store refuse the same strings.
#include <CLI/CLI.hpp>

#include "core/bake/bake_param_words.h"

namespace wavebake::cli {

struct BakeFlags {
  BakeParams params;     // the numeric flags
  BakeParamWords words;  // the named ones
};

void AddBakeFlags(CLI::App& cmd, BakeFlags& f);

}  // namespace wavebake::cli
