#include "storage/zstd_codec.h"

#include <zstd.h>

#include <memory>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

struct CCtxFree {
  void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};
struct DCtxFree {
  void operator()(ZSTD_DCtx* d) const { ZSTD_freeDCtx(d); }
};

// One context per thread: contexts are not thread-safe, and reusing one keeps
// its tables allocated between chunks.
ZSTD_CCtx* ThreadCCtx() {
  thread_local std::unique_ptr<ZSTD_CCtx, CCtxFree> cctx(ZSTD_createCCtx());
  return cctx.get();
}
ZSTD_DCtx* ThreadDCtx() {
  thread_local std::unique_ptr<ZSTD_DCtx, DCtxFree> dctx(ZSTD_createDCtx());
  return dctx.get();
}

absl::Status ZstdError(absl::string_view what, size_t code) {
  return absl::InternalError(absl::StrCat("zstd ", what, ": ", ZSTD_getErrorName(code)));
}

absl::Status Corrupt(absl::string_view source, absl::string_view why) {
  return absl::DataLossError(absl::StrCat("corrupted chunk ", source, ": ", why));
}

}  // namespace

absl::StatusOr<std::vector<std::byte>> ZstdCompress(std::span<const std::byte> src, int level) {
  if (level < ZSTD_minCLevel() || level > ZSTD_maxCLevel()) {
    return absl::InvalidArgumentError(absl::StrCat("zstd level ", level, " out of range [",
                                                   ZSTD_minCLevel(), ", ", ZSTD_maxCLevel(), "]"));
  }
  ZSTD_CCtx* cctx = ThreadCCtx();
  if (cctx == nullptr) return absl::ResourceExhaustedError("zstd: cannot create a context");
  // Reset parameters too: a failed call must not leak settings into the next chunk.
  ZSTD_CCtx_reset(cctx, ZSTD_reset_session_and_parameters);
  for (auto [param, value] :
       {std::pair{ZSTD_c_compressionLevel, level}, std::pair{ZSTD_c_contentSizeFlag, 1},
        std::pair{ZSTD_c_checksumFlag, 1}}) {
    if (size_t rc = ZSTD_CCtx_setParameter(cctx, param, value); ZSTD_isError(rc)) {
      return ZstdError("setParameter", rc);
    }
  }
  std::vector<std::byte> out(ZSTD_compressBound(src.size()));
  // ZSTD_compress2 is one-shot, so it knows the source size and writes it into the header.
  const size_t n = ZSTD_compress2(cctx, out.data(), out.size(), src.data(), src.size());
  if (ZSTD_isError(n)) return ZstdError("compress", n);
  out.resize(n);
  return out;
}

absl::Status ZstdDecompressInto(std::span<const std::byte> frame, std::span<std::byte> out,
                                absl::string_view source) {
  const size_t expected_size = out.size();
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) return Corrupt(source, "not a zstd frame");
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) {
    return Corrupt(source, "zstd frame header has no content size");
  }
  if (content != expected_size) {
    return Corrupt(source, absl::StrCat("frame holds ", content, " bytes, the chunk is ",
                                        expected_size, " bytes"));
  }
  const size_t frame_size = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
  if (ZSTD_isError(frame_size)) {
    return Corrupt(source, absl::StrCat("truncated frame: ", ZSTD_getErrorName(frame_size)));
  }
  if (frame_size != frame.size()) {
    return Corrupt(source, absl::StrCat(frame.size() - frame_size, " bytes after the frame"));
  }
  ZSTD_DCtx* dctx = ThreadDCtx();
  if (dctx == nullptr) return absl::ResourceExhaustedError("zstd: cannot create a context");
  const size_t n = ZSTD_decompressDCtx(dctx, out.data(), out.size(), frame.data(), frame.size());
  if (ZSTD_isError(n)) return Corrupt(source, ZSTD_getErrorName(n));
  if (n != expected_size) {
    return Corrupt(source, absl::StrCat("decoded ", n, " of ", expected_size, " bytes"));
  }
  return absl::OkStatus();
}

absl::StatusOr<std::vector<std::byte>> ZstdDecompress(std::span<const std::byte> frame,
                                                      size_t expected_size,
                                                      absl::string_view source) {
  std::vector<std::byte> out(expected_size);
  if (absl::Status s = ZstdDecompressInto(frame, out, source); !s.ok()) return s;
  return out;
}

}  // namespace wavebake
