#pragma once
// Display encoding shared by the PNG and PLY writers.
#include <array>
#include <cstdint>

#include "core/util/vec3.h"

namespace wavebake {

// Linear value in [0, 1] (clamped, NaN → 0) to 8-bit with the sRGB OETF.
uint8_t EncodeSrgb8(float linear);

// linear × scale, then EncodeSrgb8 per channel; any NaN channel → background
// (unscaled).
std::array<uint8_t, 3> ToneMapPixel(Vec3 linear, float scale, Vec3 background);

}  // namespace wavebake
