#pragma once
// Vertical-cross environment maps (the HDRShop / Debevec "_cross" layout):
// a 3a × 4a image of six a × a faces, the rest unused,
//
//              [ +Y ]
//        [ −X ][ −Z ][ +X ]
//              [ −Y ]
//              [ +Z ]
//
// The middle row is the view forward (−Z), left (−X) and right (+X) with +Y
// up, as in the lat-long convention (latlong.h). Every face is unfolded
// about its edge with −Z, and +Z continues below −Y, so it appears upside
// down. With face-local (a, b) ∈ [0,1]² (a to the right, b down the image),
// s = 2a − 1 and t = 2b − 1, a pixel looks along
//   +Y (s, 1, −t)   −X (−1, −t, −s)   −Z (s, −t, −1)   +X (1, −t, s)
//   −Y (s, −1, t)   +Z (s, t, 1).
#include "runtime/env/env_map.h"

namespace wavebake {

// Converts a vertical cross (width = 3a, height = 4a) to a 4a × 2a lat-long
// map. The cross's faces are exactly the texels of a Cubemap(a) (only
// reindexed), so each lat-long pixel becomes the mean of those texels over
// its footprint (sphere_overlap.h): ∫ L dω and constants are kept exactly.
EnvMap VerticalCrossToLatLong(const EnvMap& cross);

}  // namespace wavebake
