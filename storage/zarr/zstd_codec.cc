#include "storage/zarr/zstd_codec.h"

#include <zstd.h>

#include <iterator>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

struct CCtxFree {
  void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};
struct DCtxFree {
  void operator()(ZSTD_DCtx* d) const { ZSTD_freeDCtx(d); }
};

// Contexts are not thread-safe, so each call takes one from a pool and gives
// it back. A pool rather than one context per thread: FINALIZE and the
// column stage start threads per call, and a fresh context faults in its
// tables page by page. On a 1 MB chunk of transport/indices at level 9, a
// fresh context took 45 ms and 3100 page faults, a warm one 7.4 ms and none
// (this project's VMs, where a fault costs ~15 µs). Compression contexts are
// pooled by level: zstd shrinks a workspace that has been too large for a
// while, so one serving staging chunks at −3 would regrow at every return to
// level 9. The pool keeps at most as many contexts per level as ever ran at
// once, for the process's life.
template <class Ctx, class Free, Ctx* (*Make)()>
class ContextPool {
 public:
  class Lease {
   public:
    Lease(ContextPool& pool, int key, std::unique_ptr<Ctx, Free> ctx)
        : pool_(pool), key_(key), ctx_(std::move(ctx)) {}
    ~Lease() {
      if (ctx_ == nullptr) return;
      std::lock_guard lock(pool_.mu_);
      pool_.idle_.push_back({key_, std::move(ctx_)});
    }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    Ctx* get() const { return ctx_.get(); }

   private:
    ContextPool& pool_;
    int key_;
    std::unique_ptr<Ctx, Free> ctx_;
  };

  // An idle context last used with `key`, or a new one.
  Lease Take(int key) {
    {
      std::lock_guard lock(mu_);
      for (auto it = idle_.rbegin(); it != idle_.rend(); ++it) {
        if (it->first != key) continue;
        std::unique_ptr<Ctx, Free> ctx = std::move(it->second);
        idle_.erase(std::next(it).base());
        return Lease(*this, key, std::move(ctx));
      }
    }
    return Lease(*this, key, std::unique_ptr<Ctx, Free>(Make()));
  }

 private:
  std::mutex mu_;
  std::vector<std::pair<int, std::unique_ptr<Ctx, Free>>> idle_;  // guarded by mu_
};

ContextPool<ZSTD_CCtx, CCtxFree, ZSTD_createCCtx>& CCtxPool() {
  static ContextPool<ZSTD_CCtx, CCtxFree, ZSTD_createCCtx> pool;
  return pool;
}
ContextPool<ZSTD_DCtx, DCtxFree, ZSTD_createDCtx>& DCtxPool() {
  static ContextPool<ZSTD_DCtx, DCtxFree, ZSTD_createDCtx> pool;
  return pool;
}

absl::Status ZstdError(absl::string_view what, size_t code) {
  return absl::InternalError(absl::StrCat("zstd ", what, ": ", ZSTD_getErrorName(code)));
}

absl::Status Corrupt(absl::string_view source, absl::string_view why) {
  return absl::DataLossError(absl::StrCat("corrupted chunk ", source, ": ", why));
}

}  // namespace

absl::Status ZstdCompressInto(std::span<const std::byte> src, int level, ByteBuffer& frame,
                              const ZstdSearch& search) {
  if (level < ZSTD_minCLevel() || level > ZSTD_maxCLevel()) {
    return absl::InvalidArgumentError(absl::StrCat("zstd level ", level, " out of range [",
                                                   ZSTD_minCLevel(), ", ", ZSTD_maxCLevel(), "]"));
  }
  const auto lease = CCtxPool().Take(level);
  ZSTD_CCtx* cctx = lease.get();
  if (cctx == nullptr) return absl::ResourceExhaustedError("zstd: cannot create a context");
  // Reset parameters too: a failed call must not leak settings into the next chunk.
  ZSTD_CCtx_reset(cctx, ZSTD_reset_session_and_parameters);
  // A nonzero search setting replaces the level's own; 0 is zstd's "the
  // level's", so a default ZstdSearch compresses as the level alone.
  for (auto [param, value] :
       {std::pair{ZSTD_c_compressionLevel, level}, std::pair{ZSTD_c_contentSizeFlag, 1},
        std::pair{ZSTD_c_checksumFlag, 1}, std::pair{ZSTD_c_strategy, search.strategy},
        std::pair{ZSTD_c_minMatch, search.min_match}, std::pair{ZSTD_c_chainLog, search.chain_log},
        std::pair{ZSTD_c_hashLog, search.hash_log},
        std::pair{ZSTD_c_searchLog, search.search_log}}) {
    if (size_t rc = ZSTD_CCtx_setParameter(cctx, param, value); ZSTD_isError(rc)) {
      return ZstdError("setParameter", rc);
    }
  }
  frame.resize(ZSTD_compressBound(src.size()));
  // ZSTD_compress2 is one-shot, so it knows the source size and writes it into the header.
  const size_t n = ZSTD_compress2(cctx, frame.data(), frame.size(), src.data(), src.size());
  if (ZSTD_isError(n)) return ZstdError("compress", n);
  frame.resize(n);
  return absl::OkStatus();
}

absl::StatusOr<std::vector<std::byte>> ZstdCompress(std::span<const std::byte> src, int level) {
  ByteBuffer frame;
  if (absl::Status s = ZstdCompressInto(src, level, frame); !s.ok()) return s;
  return std::vector<std::byte>(frame.begin(), frame.end());
}

absl::StatusOr<uint64_t> ZstdFrameContentSize(std::span<const std::byte> frame,
                                              absl::string_view source) {
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) return Corrupt(source, "not a zstd frame");
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) {
    return Corrupt(source, "zstd frame header has no content size");
  }
  return uint64_t{content};
}

absl::Status ZstdDecompressInto(std::span<const std::byte> frame, std::span<std::byte> out,
                                absl::string_view source) {
  const size_t expected_size = out.size();
  absl::StatusOr<uint64_t> content = ZstdFrameContentSize(frame, source);
  if (!content.ok()) return content.status();
  if (*content != expected_size) {
    return Corrupt(source, absl::StrCat("frame holds ", *content, " bytes, the chunk is ",
                                        expected_size, " bytes"));
  }
  const size_t frame_size = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
  if (ZSTD_isError(frame_size)) {
    return Corrupt(source, absl::StrCat("truncated frame: ", ZSTD_getErrorName(frame_size)));
  }
  if (frame_size != frame.size()) {
    return Corrupt(source, absl::StrCat(frame.size() - frame_size, " bytes after the frame"));
  }
  const auto lease = DCtxPool().Take(0);
  ZSTD_DCtx* dctx = lease.get();
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
