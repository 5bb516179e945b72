// scratch: not for commit
#include <cstdio>
#include "runtime/glossy_store.h"
#include "runtime/lighting.h"
using namespace wavebake;
int main(int argc, char** argv) {
  GlossyOptions go; go.brdf = argv[2]; go.threads = 1;
  auto g = GlossyStore::Open(argv[1], go);
  auto env = LoadEnvMap("/work/shared/data/probes/grace.hdr");
  auto lighting = LightingFromEnv(*env, 32, WaveletFilter::kHaar);
  auto lights = SelectWaveletLights(*lighting, 256);
  std::vector<float> img(3 * (*g)->samples().cells());
  for (int rep = 0; rep < atoi(argv[3]); ++rep) (*g)->relighter().Relight(*lights, img);
  printf("%f\n", img[3*5000]);
}
