#include "cli/area_light_flags.h"

namespace wavebake::cli {

void AddAreaLightFlags(CLI::App& cmd, driver::AreaLightCommand& c) {
  cmd.add_option("--area-light", c.lights,
                 "LIGHT.json: planar area light(s) near the scene, for a store baked with "
                 "--light-domain plane:S (repeatable; the lights add)");
  cmd.add_option("--source-fraction", c.source_fraction,
                 "area lights: source coefficients kept per light")
      ->capture_default_str();
  cmd.add_option("--target-fraction", c.target_fraction,
                 "area lights: face coefficients propagated per sample")
      ->capture_default_str();
}

}  // namespace wavebake::cli
