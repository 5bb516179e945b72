// PLY uploads, ASCII and binary (tests/fuzz/scene_fuzz.h).
#include "tests/fuzz/scene_fuzz.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  binary.append(reinterpret_cast<const char*>(v), sizeof v);
  const unsigned char n = 3;
  const int f[3] = {0, 1, 2};
  binary.append(reinterpret_cast<const char*>(&n), 1);
  binary.append(reinterpret_cast<const char*>(f), sizeof f);
  return {header + "0 0 0\n2 0 0\n2 3 0\n0 3 0\n3 0 1 2\n3 0 2 3\n",
          header + "0 0 0\n2 0 0\n2 3 0\n0 3 0\n3 0 1 9\n4 0 1 2 3\n", binary,
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
          "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
          "element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
          "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n"};
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return wavebake::fuzz::FuzzSceneFile(data, size, "scene.ply");
}
