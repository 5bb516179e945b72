#pragma once
// Streams a 1-D Zarr array to disk chunk by chunk, so a writer whose array is
// larger than it wants to hold (FINALIZE's transport/indices and data,
// DESIGN.md §2 "never S×M") buffers a few chunks at a time: full chunks are
// compressed and written on helper threads while the caller fills the next
// (zstd at FINALIZE's levels is most of that task's time, and nothing else
// runs beside it), up to `in_flight` at once. The bytes written do not depend
// on this overlap. The array's length is fixed by its spec: Close() checks
// every element was appended.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <future>
#include <span>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "storage/zarr_array.h"

namespace wavebake {

template <class T>
class ArrayAppender {
 public:
  // `array` must be 1-D with element type T and outlive the appender.
  explicit ArrayAppender(const ZarrArray& array, int in_flight = 1)
      : array_(array),
        chunk_(static_cast<size_t>(array.spec().chunks.at(0))),
        in_flight_(std::max(in_flight, 1)) {}

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
    const int64_t length = array_.spec().shape.at(0);
    if (written_ != length) {
      return absl::InternalError(absl::StrCat(array_.dir().string(), ": appended ", written_,
                                              " elements to an array of ", length));
    }
    return absl::OkStatus();
  }

 private:
  // Hands the full chunk to a writer thread, once fewer than in_flight_ are
  // still writing (the oldest is waited for).
  absl::Status Flush() {
    if (pending_.size() >= static_cast<size_t>(in_flight_)) {
      if (absl::Status s = WaitOldest(); !s.ok()) return s;
    }
    std::vector<T> full(chunk_.size());
    full.swap(chunk_);
    pending_.push_back(std::async(std::launch::async,
                                  [&array = array_, index = next_chunk_, full = std::move(full)] {
                                    return array.WriteChunk<T>(std::span(&index, 1), full);
                                  }));
    ++next_chunk_;
    written_ += static_cast<int64_t>(filled_);
    filled_ = 0;
    return absl::OkStatus();
  }

  absl::Status WaitOldest() {
    absl::Status s = pending_.front().get();
    pending_.pop_front();
    return s;
  }
  absl::Status Wait() {
    absl::Status first;
    while (!pending_.empty()) {
      absl::Status s = WaitOldest();
      if (first.ok()) first = s;
    }
    return first;
  }

  const ZarrArray& array_;
  std::vector<T> chunk_;
  size_t filled_ = 0;
  int64_t next_chunk_ = 0;
  int64_t written_ = 0;
  int in_flight_;
  // The chunks being written, oldest first; std::future's destructor waits
  // for its write, so an appender dropped on an error path never outlives it.
  std::deque<std::future<absl::Status>> pending_;
};

}  // namespace wavebake
