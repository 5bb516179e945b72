#include "storage/store/transport_bytes.h"

#include <cstring>

#include "storage/zarr/byte_buffer.h"
#include "storage/zarr/delta_filter.h"
#include "storage/zarr/shuffle_filter.h"
#include "storage/zarr/zstd_codec.h"

namespace wavebake {
namespace {

constexpr int kRankingLevel = 1;

size_t Compressed(std::span<const std::byte> raw, ByteBuffer& frame) {
  if (raw.empty()) return 0;
  // Only a compressor failure (out of memory) lands here: the raw size is
  // then the bound.
  if (!ZstdCompressInto(raw, kRankingLevel, frame).ok()) return raw.size();
  return frame.size();
}

}  // namespace

size_t TransportBytes(std::span<const uint32_t> positions, std::span<const int16_t> codes) {
  thread_local ByteBuffer raw, frame;
  raw.resize(positions.size_bytes());
  if (!positions.empty()) std::memcpy(raw.data(), positions.data(), positions.size_bytes());
  DeltaEncode(DType::kUint32, raw);
  ShuffleEncode(sizeof(uint32_t), raw);
  const size_t index_bytes = Compressed(raw, frame);
  return index_bytes + Compressed(std::as_bytes(codes), frame);
}

}  // namespace wavebake
