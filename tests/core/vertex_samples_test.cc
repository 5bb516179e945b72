#include "core/layouts/vertex_samples.h"

#include <gtest/gtest.h>

#include "core/transport/ray_caster.h"
#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Disk;
using test_shapes::Quad;
using test_shapes::SceneOf;

Mesh WithNormals(Mesh m, Vec3 n) {
  m.normals.assign(m.positions.size(), n);
  return m;
}

// A wall standing on the ground's far edge: the ground's vertices there lie
// in the wall's plane. Offset along the normal only, their rays start on the
// wall and every one meets it at t = 0; moved into the ground, a vertex sees
// the wall behind it and the sky in front, as the ground beside it does.
TEST(VertexSamplesTest, BoundaryVerticesMoveOffTheSurfaceTheyAbut) {
  const Mesh ground = WithNormals(Quad({0, 0, 0}, {0, 1, 0}, 1, "ground"), {0, 1, 0});
  const Mesh wall = WithNormals(Quad({0, 1, -1}, {0, 0, 1}, 1, "wall"), {0, 0, 1});
  const Scene scene = SceneOf({ground, wall});
  const RayCaster caster = BuildOrDie(scene);
  const float eps = 1e-3f;
  const SampleSet flush = VertexSamples(scene, 0), inset = VertexSamples(scene, eps);
  const Vec3 away = Normalize(Vec3{0, 1, 1}), towards = Normalize(Vec3{0, 1, -1});
  int at_wall = 0;
  for (int v = 0; v < 4; ++v) {  // the ground's vertices
    EXPECT_NEAR(Length(inset.position[v] - flush.position[v]), eps, 1e-6f);
    EXPECT_EQ(inset.position[v].y, 0.0f);  // moved in the ground's plane
    if (flush.position[v].z != -1.0f) continue;
    ++at_wall;
    const Vec3 o0 = flush.position[v] + Vec3{0, 1, 0} * eps;
    const Vec3 o1 = inset.position[v] + Vec3{0, 1, 0} * eps;
    EXPECT_TRUE(caster.Occluded(o0, away, 0, 1e30f)) << "the flush vertex reads as black";
    EXPECT_FALSE(caster.Occluded(o1, away, 0, 1e30f)) << "vertex " << v;
    EXPECT_TRUE(caster.Occluded(o1, towards, 0, 1e30f)) << "vertex " << v;
  }
  EXPECT_EQ(at_wall, 2);
}

// Interior vertices stay where they are; rim vertices move towards the inside.
TEST(VertexSamplesTest, InteriorVerticesStay) {
  const Scene scene = SceneOf({WithNormals(Disk({0, 0, 0}, {0, 0, 1}, 1, 16), {0, 0, 1})});
  const SampleSet s = VertexSamples(scene, 0.01f);
  EXPECT_EQ(s.position[0], scene.meshes[0].positions[0]);
  for (int v = 1; v <= 16; ++v) EXPECT_NEAR(Length(s.position[v]), 0.99f, 1e-5f) << v;
}

}  // namespace
}  // namespace wavebake
