#pragma once
// Every vertex of a scene's meshes as a sample: the auxiliary set that the
// bounces of a camera layout gather from (core/bake/bake_gather.h). A
// camera's pixels are points on the surfaces, but only those it sees; the
// light a pixel receives by one bounce comes from surfaces it may not see,
// so the previous bounce is interpolated over the meshes' own vertices.
#include <cstdint>

#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake {

// S = VertexCount(scene) samples in mesh order: sample = cell = global vertex
// id (samples.vertex the identity), the mesh's normals and albedo; a 1-row
// grid (width S, height 1: no image, nothing transforms over it). The meshes
// must have been through CheckAndRepairScene (normals).
//
// A vertex on the boundary of its mesh (an edge that one triangle uses) is
// moved `inset` into its triangles: such a vertex is where a mesh rests on
// or abuts another (a box on the floor, a wall on the ground's edge), so its
// ray origin, offset along the normal only, lies on the other surface, and
// every ray meets that surface at t = 0: the vertex would read as black.
// Moved inward it sees the other surface where it stands and the sky
// elsewhere, as the surface just beside it does. Interior vertices stay.
SampleSet VertexSamples(const Scene& scene, float inset = 0);
int64_t VertexCount(const Scene& scene);

}  // namespace wavebake
