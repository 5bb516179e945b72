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
SampleSet VertexSamples(const Scene& scene);
int64_t VertexCount(const Scene& scene);

}  // namespace wavebake
