#pragma once
// Tessellated primitives the built-in scenes are made of. Each appends to a
// Mesh (so several shapes can share one mesh and one albedo) with exact
// per-vertex normals, and winds every triangle so its geometric normal agrees
// with them: rays and the layouts rely on that orientation.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/scene/scene.h"

namespace wavebake {

struct SurfacePoint {
  Vec3 position, normal;
};

// A patch of nu×nv vertices f(i, j), i < nu, j < nv (integer indices so
// callers place grid vertices exactly); vertex (i, j) gets id first + j*nu + i,
// so a patch is a regular grid in the sense of Mesh. With wrap_u the last
// column joins the first — for closed rings. Triangles face ∂p/∂j × ∂p/∂i.
// Returns first, the id of vertex (0, 0).
using PatchFn = std::function<SurfacePoint(int i, int j)>;
uint32_t AppendPatch(Mesh& mesh, int nu, int nv, bool wrap_u, const PatchFn& f);

// A triangle fan from a new centre vertex to existing vertices `ring` (a
// closed loop), wound so the triangles face `centre.normal`.
void AppendFan(Mesh& mesh, SurfacePoint centre, const std::vector<uint32_t>& ring);

// A closed loop of `segments` new vertices on the circle of `radius` around
// `centre` in the plane y = centre.y, all with normal `normal`. Returns ids.
std::vector<uint32_t> AppendCircle(Mesh& mesh, Vec3 centre, float radius, int segments,
                                   Vec3 normal);

// Height field y = height(x, z) over the square [x0, x0 + (n-1)*spacing] ×
// [z0, ...] as an n×n regular grid (vertex (i, j) at x0 + i*spacing,
// z0 + j*spacing), normals from the height field's gradient, facing up.
Mesh MakeHeightField(std::string name, int n, float x0, float z0, float spacing,
                     const std::function<float(float x, float z)>& height);

// Open cylinder side (axis +Y, base centre `base`) plus a top cap.
void AppendCylinder(Mesh& mesh, Vec3 base, float radius, float height, int segments, int rows);

// Axis-aligned box without its bottom face (it stands on the ground), each
// face an n×n grid so vertex layouts see more than its corners.
void AppendOpenBox(Mesh& mesh, Vec3 min_corner, Vec3 max_corner, int n);

// UV sphere: `rings` latitude rings of `segments` vertices plus two poles.
void AppendSphere(Mesh& mesh, Vec3 centre, float radius, int segments, int rings);

}  // namespace wavebake
