// TEMPORARY diagnostics (not committed).
#include <cmath>
#include <cstdio>
#include "runtime/area_reference.h"
#include "runtime/eval.h"
#include "runtime/image_io.h"
#include "runtime/near_field.h"
using namespace wavebake;
int main(int argc, char** argv) {
  auto st = *OpenNearFieldStore(argv[1]);
  auto lights = *LoadAreaLights(argv[2]);
  auto caster = *BuildBakedScene(st.info);
  AreaReferenceOptions o; o.axis = st.face.axis(); o.epsilon = BakedEpsilon(st.info, caster);
  o.batches = 16;
  auto ref = *ComputeAreaReference(caster, st.samples, lights, o);
  std::vector<float> rgb(3 * st.samples.cells());
  RelightNearField(st, lights, {1, 1, nullptr, 2}, rgb);
  int w = st.samples.width, h = st.samples.height;
  std::vector<float> err(rgb.size());
  double e2 = 0, r2 = 0;
  // per-region: by normal
  double en[3] = {0,0,0}, rn[3] = {0,0,0};
  for (int c = 0; c < w * h; ++c) {
    int id = st.samples.grid[c];
    if (id < 0) { for (int k=0;k<3;++k) err[3*c+k] = NAN; continue; }
    Vec3 n = st.samples.normal[id];
    int cls = n.y > 0.9 ? 0 : (n.z > 0.9 ? 1 : 2);
    double d = 0, r = 0;
    for (int k = 0; k < 3; ++k) { double x = rgb[3*c+k] - ref.rgb[3*c+k]; d += x*x; r += ref.rgb[3*c+k]*ref.rgb[3*c+k]; }
    en[cls] += d; rn[cls] += r; e2 += d; r2 += r;
    float v = std::sqrt(d / 3);
    err[3*c] = v > 0 ? v * 10 : 0; err[3*c+1] = 0; err[3*c+2] = rgb[3*c] < ref.rgb[3*c] ? v*10 : 0;
  }
  printf("total %.4f  up %.4f (share %.3f) wall %.4f (share %.3f) other %.4f (share %.3f)\n", std::sqrt(e2/r2),
    std::sqrt(en[0]/rn[0]), en[0]/e2, std::sqrt(en[1]/rn[1]), en[1]/e2, std::sqrt(en[2]/rn[2]), en[2]/e2);
  WritePng("out/diag_near.png", w, h, rgb, 0, {0,0,0});
  WritePng("out/diag_ref.png", w, h, ref.rgb, 0, {0,0,0});
  WritePng("out/diag_err.png", w, h, err, 0, {0,0,0});
}
