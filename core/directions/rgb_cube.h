#pragma once
// A dense RGB vector over the cubemap's row basis (rgb[3m + c], m = face·N²
// + y·N + x) that remembers which faces were written: the per-sample weights
// W(x) of DESIGN.md §1 "Per-sample lighting", filled by the Haar product
// (core/products/haar_product.h) or any other per-sample lighting, read by the
// per-sample rows (runtime/relight/sample_rows.h). Clearing costs the touched faces
// only, so one cube serves every sample of a frame.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace wavebake {

struct RgbCube {
  explicit RgbCube(int n) : n(n), rgb(static_cast<size_t>(18) * n * n, 0.0f) {}

  size_t face_size() const { return 3 * static_cast<size_t>(n) * n; }
  float* face(int f) { return rgb.data() + f * face_size(); }
  const float* face(int f) const { return rgb.data() + f * face_size(); }
  // Zeroes the touched faces and forgets them.
  void Clear() {
    for (int f = 0; f < 6; ++f) {
      if (!touched[f]) continue;
      std::fill_n(face(f), face_size(), 0.0f);
      touched[f] = false;
    }
  }

  int n = 0;
  std::vector<float> rgb;
  std::array<bool, 6> touched{};
};

}  // namespace wavebake
