#include "cli/app.h"

#include <CLI/CLI.hpp>

namespace wavebake::cli {

int Run(int argc, char** argv) {
  CLI::App app{"wavebake: bake, compress and relight all-frequency light transport"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return 0;
}

}  // namespace wavebake::cli
