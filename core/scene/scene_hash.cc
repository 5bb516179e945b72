#include "core/scene/scene_hash.h"

#include <bit>
#include <cstdint>

#include "absl/strings/str_format.h"

namespace wavebake {
namespace {

constexpr uint64_t kC1 = 0x87c37b91114253d5ull, kC2 = 0x4cf5ad432745937full;

constexpr uint64_t Fmix(uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return k;
}

// Two-lane 128-bit hash in the style of MurmurHash3 x64-128 over 16-byte
// blocks; the stream is zero-padded and its length mixed in at the end.
// Not cryptographic: it names content, it does not defend against forgery.
class Hasher128 {
 public:
  void Byte(uint8_t b) {
    block_[fill_++] = b;
    ++length_;
    if (fill_ == 16) Flush();
  }
  void U32(uint32_t v) {
    for (int i = 0; i < 4; ++i) Byte(static_cast<uint8_t>(v >> (8 * i)));  // little-endian
  }
  void I32(int32_t v) { U32(static_cast<uint32_t>(v)); }
  void F32(float f) { U32(std::bit_cast<uint32_t>(f == 0 ? 0.0f : f)); }
  void V3(Vec3 v) {
    F32(v.x);
    F32(v.y);
    F32(v.z);
  }
  void Tag(const char* s) {
    for (; *s; ++s) Byte(static_cast<uint8_t>(*s));
    Byte(0);
  }

  std::string Hex() {
    const uint64_t length = length_;
    while (fill_ != 0) Byte(0);
    uint64_t h1 = h1_ ^ length, h2 = h2_ ^ length;
    h1 += h2;
    h2 += h1;
    h1 = Fmix(h1);
    h2 = Fmix(h2);
    h1 += h2;
    h2 += h1;
    return absl::StrFormat("%016x%016x", h1, h2);
  }

 private:
  static uint64_t Rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
  uint64_t Word(int at) const {
    uint64_t w = 0;
    for (int i = 7; i >= 0; --i) w = (w << 8) | block_[at + i];
    return w;
  }
  void Flush() {
    const uint64_t k1 = Rotl(Word(0) * kC1, 31) * kC2;
    const uint64_t k2 = Rotl(Word(8) * kC2, 33) * kC1;
    h1_ = Rotl(h1_ ^ k1, 27) + h2_;
    h1_ = h1_ * 5 + 0x52dce729;
    h2_ = Rotl(h2_ ^ k2, 31) + h1_;
    h2_ = h2_ * 5 + 0x38495ab5;
    fill_ = 0;
  }

  uint8_t block_[16] = {};
  int fill_ = 0;
  uint64_t length_ = 0;
  // Fixed, arbitrary seeds (the first 128 bits of the fractional part of π).
  uint64_t h1_ = 0x243f6a8885a308d3ull, h2_ = 0x13198a2e03707344ull;
};

}  // namespace

std::string SceneHash(const Scene& scene, int uv_channel) {
  Hasher128 h;
  // Bump the version tag whenever the serialization changes: old hashes must
  // not silently match new content.
  h.Tag("wavebake-scene/1");
  h.U32(static_cast<uint32_t>(scene.meshes.size()));
  for (const Mesh& m : scene.meshes) {
    h.Tag("mesh");
    h.U32(static_cast<uint32_t>(m.positions.size()));
    for (Vec3 p : m.positions) h.V3(p);
    h.U32(static_cast<uint32_t>(m.normals.size()));
    for (Vec3 n : m.normals) h.V3(n);
    h.U32(static_cast<uint32_t>(m.triangles.size()));
    for (const auto& t : m.triangles)
      for (uint32_t v : t) h.U32(v);
    h.V3(m.albedo);
    h.I32(m.grid_width);
    h.I32(m.grid_height);
  }
  if (uv_channel >= 0) {  // only then: every other layout's hash stays as it was
    h.Tag("uv-channel");
    h.I32(uv_channel);
    for (const Mesh& m : scene.meshes) {
      const bool has = static_cast<size_t>(uv_channel) < m.uv_channels.size();
      h.U32(has ? static_cast<uint32_t>(m.uv_channels[uv_channel].size()) : 0u);
      if (!has) continue;
      for (Vec2 t : m.uv_channels[uv_channel]) {
        h.F32(t.u);
        h.F32(t.v);
      }
    }
  }
  h.Tag(scene.camera ? "camera" : "no-camera");
  if (scene.camera) {
    h.V3(scene.camera->eye);
    h.V3(scene.camera->target);
    h.V3(scene.camera->up);
    h.F32(scene.camera->fov_y_degrees);
  }
  return h.Hex();
}

}  // namespace wavebake
