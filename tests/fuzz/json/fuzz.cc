// JSON scene uploads (storage/scene_files/scene_loader_json.cc), their mesh references
// resolved inside the upload, where tri.obj lies (tests/fuzz/scene_fuzz.h).
#include "tests/fuzz/scene_fuzz.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  return {R"({"meshes": [{"file": "tri.obj"}]})",
          R"({"meshes": [{"file": "tri.obj", "albedo": [0.5, 0.25, 1],
                          "transform": {"scale": [2, -1, 1], "rotate_y_degrees": 30,
                                        "translate": [1, 2, 3]}},
                         {"file": "./tri.obj", "transform": {"scale": 0.5}}],
              "camera": {"eye": [0, 1, 5], "target": [0, 0, 0], "up": [0, 1, 0],
                         "fov_y_degrees": 45}})",
          R"({"meshes": [{"file": "../outside.obj"}]})",
          R"({"meshes": [{"file": "/etc/passwd"}]})",
          R"({"meshes": [{"file": "tri.obj"}], "camera": {"eye": [0, 0, 0], "target": [0, 0, 0]}})",
          R"({"meshes": [{"file": "scene.json"}]})"};
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return wavebake::fuzz::FuzzSceneFile(data, size, "scene.json");
}
