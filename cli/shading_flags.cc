#include "cli/shading_flags.h"

#include "cli/command_error.h"

namespace wavebake::cli {

void AddGlossyFlags(CLI::App& cmd, GlossyFlags& f) {
  cmd.add_option("--brdf", f.options.brdf,
                 "material (visibility stores; a diffuse store is lambert): lambert | phong:EXP "
                 "| blinn:EXP | ggx:ROUGHNESS")
      ->capture_default_str();
  cmd.add_option("--brdf-terms", f.options.slices.terms,
                 "Haar coefficients kept per sample's BRDF slice (0: all)")
      ->capture_default_str();
  cmd.add_option("--view", f.view,
                 "X,Y,Z eye position for glossy BRDFs on mesh layouts (camera layouts use the "
                 "baked camera)");
}

GlossyOptions GlossyOf(const GlossyFlags& f, const char* command) {
  GlossyOptions g = f.options;
  if (!f.view.empty()) {
    absl::StatusOr<Vec3> eye = ParseView(f.view);
    if (!eye.ok()) Fail(command, eye.status());
    g.eye = *eye;
  }
  return g;
}

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
