#pragma once
// Helpers shared by the runtime tests: synthetic environments, sums over the
// cubemap, scratch directories.
#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/directions/cubemap.h"
#include "runtime/env/env_map.h"

namespace wavebake::testing {

inline EnvMap UniformEnv(int width, int height, float value) {
  return {width, height, std::vector<float>(size_t(width) * height * 3, value)};
}

inline void SetPixel(EnvMap& env, int x, int y, Vec3 v) {
  float* p = &env.rgb[(size_t(y) * env.width + x) * 3];
  p[0] = v.x, p[1] = v.y, p[2] = v.z;
}

// Σ_m L_m Ω_m of one channel over the texels of `face` (or all faces if -1):
// what B = T·L sees of the lighting.
inline double CubeEnergy(std::span<const float> rgb, const Cubemap& cube, int channel,
                         int face = -1) {
  double total = 0;
  for (int m = 0; m < cube.size(); ++m) {
    if (face < 0 || cube.TexelOf(m).face == face)
      total += rgb[3 * m + channel] * cube.SolidAngle(m);
  }
  return total;
}

// A fresh directory per test, under gtest's temp dir.
inline std::filesystem::path ScratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "wavebake_runtime" /
                              (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string ProbePath(const char* name) {
  return std::string(WB_SHARED_DATA) + "/probes/" + name;
}

}  // namespace wavebake::testing
