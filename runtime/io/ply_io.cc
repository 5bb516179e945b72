// PLY half of image_io.h.
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "runtime/io/image_io.h"
#include "runtime/io/tonemap.h"
#include "storage/files/atomic_file.h"

namespace wavebake {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer emits binary_little_endian by copying memory");

template <typename T>
void Append(std::vector<std::byte>& out, const T& value) {
  const auto* p = reinterpret_cast<const std::byte*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

std::string PlyHeader(size_t vertices, size_t faces) {
  return absl::StrCat(
      "ply\nformat binary_little_endian 1.0\ncomment wavebake relight\n", "element vertex ",
      vertices, "\nproperty float x\nproperty float y\nproperty float z\n",
      "property uchar red\nproperty uchar green\nproperty uchar blue\n", "element face ", faces,
      "\nproperty list uchar int vertex_indices\nend_header\n");
}

absl::Status CheckMesh(const std::filesystem::path& path, size_t vertices,
                       std::span<const std::array<uint32_t, 3>> triangles, size_t rgb_values) {
  if (rgb_values != vertices * 3) {
    return absl::InvalidArgumentError(absl::StrCat(path.string(), ": ", vertices, " vertices need ",
                                                   vertices * 3, " colour values, got ",
                                                   rgb_values));
  }
  for (size_t f = 0; f < triangles.size(); ++f) {
    for (uint32_t v : triangles[f]) {
      if (v >= vertices) {
        return absl::InvalidArgumentError(
            absl::StrCat(path.string(), ": triangle ", f, " uses vertex ", v, " of ", vertices));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status WritePlyVertexColors(const std::filesystem::path& path,
                                  std::span<const Vec3> positions,
                                  std::span<const std::array<uint32_t, 3>> triangles,
                                  std::span<const float> rgb_per_vertex, float exposure_stops) {
  if (absl::Status s = CheckMesh(path, positions.size(), triangles, rgb_per_vertex.size());
      !s.ok()) {
    return s;
  }
  const std::string header = PlyHeader(positions.size(), triangles.size());
  std::vector<std::byte> out(reinterpret_cast<const std::byte*>(header.data()),
                             reinterpret_cast<const std::byte*>(header.data() + header.size()));
  out.reserve(out.size() + positions.size() * 15 + triangles.size() * 13);
  const float scale = std::exp2(exposure_stops);
  for (size_t v = 0; v < positions.size(); ++v) {
    const float* c = &rgb_per_vertex[3 * v];
    Append(out, positions[v].x), Append(out, positions[v].y), Append(out, positions[v].z);
    for (uint8_t byte : ToneMapPixel({c[0], c[1], c[2]}, scale, Vec3{})) Append(out, byte);
  }
  for (const auto& t : triangles) {
    Append(out, uint8_t{3});
    for (uint32_t v : t) Append(out, static_cast<int32_t>(v));
  }
  return AtomicWriteFile(path, out);
}

absl::Status WritePlyVertexColors(const std::filesystem::path& path, const Scene& scene,
                                  std::span<const float> rgb_per_vertex, float exposure_stops) {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  for (const Mesh& mesh : scene.meshes) {
    const auto offset = static_cast<uint32_t>(positions.size());
    positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
    for (const auto& t : mesh.triangles) {
      triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  return WritePlyVertexColors(path, positions, triangles, rgb_per_vertex, exposure_stops);
}

}  // namespace wavebake
