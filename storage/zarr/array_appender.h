#pragma once
// Streams a 1-D Zarr array to disk chunk by chunk, so a writer whose array is
// larger than it wants to hold (FINALIZE's transport/indices and data,
// DESIGN.md §2 "never S×M") buffers a few chunks at a time: full chunks are
// compressed and written by `in_flight` writer threads while the caller fills
// the next (zstd at FINALIZE's levels is most of that task's time, and
// nothing else runs beside it). The writers live as long as the appender and
// the chunk buffers go round, so no chunk pays for a thread or a fresh
// buffer (storage/zarr/zstd_codec.cc: what a fresh zstd context costs). The bytes
// written do not depend on the overlap. The array's length is fixed by its
// spec: Close() checks every element was appended.
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {

template <class T>
class ArrayAppender {
 public:
  // `array` must be 1-D with element type T and outlive the appender. It
  // writes chunks from `first_chunk` on, `length` elements (-1: up to the
  // array's end), so writers of disjoint chunk ranges can share an array
  // (FINALIZE's shards); only the array's last chunk may end short.
  explicit ArrayAppender(const ZarrArray& array, int in_flight = 1, int64_t first_chunk = 0,
                         int64_t length = -1)
      : array_(array),
        chunk_(static_cast<size_t>(array.spec().chunks.at(0))),
        next_chunk_(first_chunk),
        length_(length >= 0 ? length
                            : array.spec().shape.at(0) - first_chunk * array.spec().chunks.at(0)),
        in_flight_(std::max(in_flight, 1)) {}

  // Waits for the chunks handed over (an appender dropped on an error path
  // never outlives its writes).
  ~ArrayAppender() {
    {
      std::lock_guard lock(mu_);
      closing_ = true;
    }
    work_.notify_all();
    writers_.clear();  // joins
  }

  ArrayAppender(const ArrayAppender&) = delete;
  ArrayAppender& operator=(const ArrayAppender&) = delete;

  absl::Status Append(std::span<const T> values) {
    while (!values.empty()) {
      const size_t n = std::min(values.size(), chunk_.size() - filled_);
      std::copy_n(values.begin(), n, chunk_.begin() + filled_);
      filled_ += n;
      values = values.subspan(n);
      if (filled_ == chunk_.size()) {
        if (absl::Status s = Flush(); !s.ok()) return s;
      }
    }
    return absl::OkStatus();
  }

  // Writes the last, partial chunk (padded with the fill value, as Zarr
  // does) and checks the length.
  absl::Status Close() {
    if (filled_ > 0) {
      std::fill(chunk_.begin() + filled_, chunk_.end(), static_cast<T>(array_.spec().fill_value));
      if (absl::Status s = Flush(); !s.ok()) return s;
    }
    if (absl::Status s = Wait(); !s.ok()) return s;
    if (written_ != length_) {
      return absl::InternalError(absl::StrCat(array_.dir().string(), ": appended ", written_,
                                              " elements where ", length_, " were due"));
    }
    return absl::OkStatus();
  }

 private:
  struct Chunk {
    int64_t index;
    std::vector<T> values;
  };

  // Hands the full chunk to the writers once fewer than in_flight_ are
  // queued or being written, and takes a written chunk's buffer in its place.
  absl::Status Flush() {
    std::vector<T> next;
    {
      std::unique_lock lock(mu_);
      done_.wait(lock, [&] { return queued_.size() + writing_ < size_t(in_flight_); });
      if (!error_.ok()) return error_;
      if (!spare_.empty()) {
        next = std::move(spare_.back());
        spare_.pop_back();
      }
      next.resize(chunk_.size());  // Append overwrites it before it is flushed
      next.swap(chunk_);
      queued_.push_back({next_chunk_, std::move(next)});
    }
    if (writers_.empty())
      for (int i = 0; i < in_flight_; ++i) writers_.emplace_back([this] { WriteQueued(); });
    work_.notify_one();
    ++next_chunk_;
    written_ += static_cast<int64_t>(filled_);
    filled_ = 0;
    return absl::OkStatus();
  }

  // A writer thread: queued chunks until the appender closes.
  void WriteQueued() {
    std::unique_lock lock(mu_);
    while (true) {
      work_.wait(lock, [&] { return closing_ || !queued_.empty(); });
      if (queued_.empty()) return;
      Chunk chunk = std::move(queued_.front());
      queued_.pop_front();
      ++writing_;
      lock.unlock();
      absl::Status s = array_.WriteChunk<T>(std::span(&chunk.index, 1), chunk.values);
      lock.lock();
      --writing_;
      if (error_.ok()) error_ = std::move(s);
      spare_.push_back(std::move(chunk.values));
      done_.notify_all();
    }
  }

  // Every chunk handed over written; the first error, if any.
  absl::Status Wait() {
    std::unique_lock lock(mu_);
    done_.wait(lock, [&] { return queued_.empty() && writing_ == 0; });
    return error_;
  }

  const ZarrArray& array_;
  std::vector<T> chunk_;  // being filled by Append
  size_t filled_ = 0;
  int64_t next_chunk_ = 0;
  const int64_t length_;  // elements due from next_chunk_'s start
  int64_t written_ = 0;
  const int in_flight_;

  std::mutex mu_;
  std::condition_variable work_, done_;
  std::deque<Chunk> queued_;           // guarded by mu_
  size_t writing_ = 0;                 // guarded by mu_
  std::vector<std::vector<T>> spare_;  // written chunks' buffers; guarded by mu_
  absl::Status error_;                 // the first write error; guarded by mu_
  bool closing_ = false;               // guarded by mu_
  std::vector<std::jthread> writers_;  // started by the first Flush
};

}  // namespace wavebake
