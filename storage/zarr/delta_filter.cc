#include "storage/zarr/delta_filter.h"

#include <cstdint>
#include <cstring>

namespace wavebake {
namespace {

// memcpy loads/stores: a chunk span need not be aligned for U.
template <class U>
U Load(const std::byte* p) {
  U v;
  std::memcpy(&v, p, sizeof(U));
  return v;
}
template <class U>
void Store(std::byte* p, U v) {
  std::memcpy(p, &v, sizeof(U));
}

template <class U>
void Encode(std::span<std::byte> chunk) {
  U prev = 0;
  for (size_t i = 0; i + sizeof(U) <= chunk.size(); i += sizeof(U)) {
    const U cur = Load<U>(chunk.data() + i);
    Store<U>(chunk.data() + i, static_cast<U>(cur - prev));
    prev = cur;
  }
}

template <class U>
void Decode(std::span<std::byte> chunk) {
  U sum = 0;
  for (size_t i = 0; i + sizeof(U) <= chunk.size(); i += sizeof(U)) {
    sum = static_cast<U>(sum + Load<U>(chunk.data() + i));
    Store<U>(chunk.data() + i, sum);
  }
}

// Unsigned arithmetic of the element's width: wraps like numpy, no UB.
template <template <class> class Op>
void Dispatch(DType dtype, std::span<std::byte> chunk) {
  switch (ItemSize(dtype)) {
    case 1:
      return Op<uint8_t>{}(chunk);
    case 2:
      return Op<uint16_t>{}(chunk);
    case 4:
      return Op<uint32_t>{}(chunk);
    default:
      return Op<uint64_t>{}(chunk);
  }
}

template <class U>
struct EncodeOp {
  void operator()(std::span<std::byte> c) const { Encode<U>(c); }
};
template <class U>
struct DecodeOp {
  void operator()(std::span<std::byte> c) const { Decode<U>(c); }
};

}  // namespace

void DeltaEncode(DType dtype, std::span<std::byte> chunk) { Dispatch<EncodeOp>(dtype, chunk); }
void DeltaDecode(DType dtype, std::span<std::byte> chunk) { Dispatch<DecodeOp>(dtype, chunk); }

}  // namespace wavebake
