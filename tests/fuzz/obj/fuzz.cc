// Wavefront OBJ uploads (tests/fuzz/scene_fuzz.h).
#include "tests/fuzz/scene_fuzz.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  return {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
          "mtllib red.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nusemtl red\n"
          "f 1//1 2//1 3//1 4//1\n",
          "mtllib ../outside.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n",
          "o a\nv 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nf 1 2 3\nf 1 3 4\ng b\nf -1 -2 -3\n",
          "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n",
          "v 0 0 0\nv 1 0 0\nvt 0 0\nvt 1 0\nvt 0 1\nv 0 1 0\nf 1/1 2/2 3/3\nl 1 2\np 3\n"};
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return wavebake::fuzz::FuzzSceneFile(data, size, "scene.obj");
}
