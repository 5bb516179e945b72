// Vertical-cross files: faces where env_cross.h draws them, energy kept.
#include "runtime/env/env_cross.h"

#include <gtest/gtest.h>

#include "env_test_util.h"
#include "runtime/env/env_resample.h"
#include "runtime/io/image_io.h"

namespace wavebake {
namespace {

using testing::CubeEnergy;

constexpr int kA = 32;  // face edge in pixels

// (column, row) of each cube face in the cross, in face units.
struct Slot {
  int face, col, row;
};
constexpr Slot kSlots[] = {{kPosY, 1, 0}, {kNegX, 0, 1}, {kNegZ, 1, 1},
                           {kPosX, 2, 1}, {kNegY, 1, 2}, {kPosZ, 1, 3}};

// Face f is filled with `value(f)`; the unused corners hold junk that must
// not leak in.
template <typename Value>
EnvMap MakeCross(Value value) {
  EnvMap cross = testing::UniformEnv(3 * kA, 4 * kA, 99);
  for (const Slot& s : kSlots) {
    for (int j = 0; j < kA; ++j) {
      for (int i = 0; i < kA; ++i)
        testing::SetPixel(cross, s.col * kA + i, s.row * kA + j, value(s.face, i, j));
    }
  }
  return cross;
}

absl::StatusOr<EnvMap> SaveAndLoad(const EnvMap& cross) {
  const auto path = testing::ScratchDir() / "cross.exr";
  if (absl::Status s = WriteExr(path, cross.width, cross.height, cross.rgb); !s.ok()) return s;
  return LoadEnvMap(path.string());
}

TEST(CrossTest, FacesLandOnTheirCubeFaces) {
  const absl::StatusOr<EnvMap> env = SaveAndLoad(MakeCross([](int face, int, int) {
    return Vec3{1.0f + face, 0, 0};
  }));
  ASSERT_TRUE(env.ok()) << env.status();
  EXPECT_EQ(env->width, 2 * env->height);
  const Cubemap cube(8);
  const std::vector<float> l = ResampleToCubemap(*env, cube);
  for (int m = 0; m < cube.size(); ++m) {
    const Texel t = cube.TexelOf(m);
    // Texels a whole texel away from the face edges see only their own face.
    if (t.x == 0 || t.y == 0 || t.x == 7 || t.y == 7) continue;
    ASSERT_NEAR(l[3 * m], 1.0f + t.face, 1e-5)
        << "face " << t.face << " (" << t.x << ", " << t.y << ")";
  }
}

// A bright pixel near the top edge of the upside-down +Z face, left of its
// centre: by the table in env_cross.h it looks along (−0.5, −0.8, 1), which
// checks the orientation within a face, not just the face.
TEST(CrossTest, BackFaceIsUpsideDown) {
  const int i = kA / 4, j = kA / 10;  // a ≈ 0.25, b ≈ 0.1
  const absl::StatusOr<EnvMap> env = SaveAndLoad(MakeCross([&](int face, int x, int y) {
    return Vec3{face == kPosZ && x == i && y == j ? 1000.0f : 0.0f, 0, 0};
  }));
  ASSERT_TRUE(env.ok()) << env.status();
  const Cubemap cube(8);
  const std::vector<float> l = ResampleToCubemap(*env, cube);
  int brightest = 0;
  for (int m = 0; m < cube.size(); ++m) {
    if (l[3 * m] * cube.SolidAngle(m) > l[3 * brightest] * cube.SolidAngle(brightest))
      brightest = m;
  }
  const float s = 2 * (i + 0.5f) / kA - 1, t = 2 * (j + 0.5f) / kA - 1;
  EXPECT_EQ(brightest, cube.Lookup({s, t, 1}));
}

// A cross pixel covers exactly the solid angle of the same texel of a
// Cubemap(a), whatever the face's orientation, so ∫ L dω of the file is
// known independently of the conversion.
TEST(CrossTest, KeepsTheSphereIntegral) {
  auto value = [](int face, int x, int y) {
    const bool lamp = (x / 3 + y / 3 + face) % 11 == 0 && x % 3 == 0 && y % 3 == 0;
    return Vec3{0.5f + 0.1f * face, 1.0f + 0.02f * x, lamp ? 50.0f : 1.0f};
  };
  const Cubemap faces(kA);
  double expected[3] = {0, 0, 0};
  for (const Slot& s : kSlots) {
    for (int j = 0; j < kA; ++j) {
      for (int i = 0; i < kA; ++i) {
        const double omega = faces.SolidAngle(faces.Index({0, i, j}));
        for (int c = 0; c < 3; ++c) expected[c] += omega * value(s.face, i, j)[c];
      }
    }
  }
  const absl::StatusOr<EnvMap> env = SaveAndLoad(MakeCross(value));
  ASSERT_TRUE(env.ok()) << env.status();
  const Cubemap cube(16);
  const std::vector<float> l = ResampleToCubemap(*env, cube);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(SphereIntegral(*env, c), expected[c], 1e-5 * expected[c]) << "channel " << c;
    EXPECT_NEAR(CubeEnergy(l, cube, c), expected[c], 1e-5 * expected[c]) << "channel " << c;
  }
}

}  // namespace
}  // namespace wavebake
