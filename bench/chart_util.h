#pragma once
// What the chart generators (bench/charts_data.cc, bench/charts_runtime.cc)
// share: dying loudly on an error (a chart must not be drawn from a partial
// sweep) and CSV output. Header-only: every bench/*.cc is its own binary.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/util/parallel_for.h"

namespace wavebake::charts {

// Set by each generator's main() for its messages.
inline const char* program = "bench_charts";

[[noreturn]] inline void Die(const std::string& what) {
  std::fprintf(stderr, "%s: %s\n", program, what.c_str());
  std::exit(1);
}

inline void Check(const absl::Status& s) {
  if (!s.ok()) Die(s.ToString());
}

template <typename T>
T Value(absl::StatusOr<T> v) {
  if (!v.ok()) Die(v.status().ToString());
  return *std::move(v);
}

// task(0..count-1) on `threads` threads; the first failure dies
// (bench/charts_uv.cc's in-place staging and coding).
inline void RunTasksOrDie(int count, int threads, const std::function<absl::Status(int)>& task) {
  Check(ParallelTasks(count, threads, task));
}

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A header, then rows of already formatted fields, flushed row by row so a
// long sweep's CSV can be watched.
class Csv {
 public:
  Csv(const std::filesystem::path& path, const std::string& header) : out_(path) {
    if (!out_) Die("cannot write " + path.string());
    out_ << header << '\n';
  }
  template <typename... Fields>
  void Row(const Fields&... fields) {
    const char* sep = "";
    ((out_ << sep << fields, sep = ","), ...);
    out_ << '\n';
    out_.flush();
  }

 private:
  std::ofstream out_;
};

}  // namespace wavebake::charts
