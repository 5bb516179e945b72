#pragma once
// Shared by the libFuzzer harnesses (tests/fuzz/<name>/fuzz.cc): a private
// scratch directory, writing an input to a file, invariant checks that abort
// (a finding), and seed writing: WB_FUZZ_WRITE_SEEDS=DIR fuzz_<name> -runs=0
// writes the harness's Seeds() to DIR (how tests/fuzz/<name>/corpus/ was made).
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace wavebake::fuzz {

// Defined by each harness: the inputs its corpus starts from.
std::vector<std::string> Seeds();

// Removed at exit; one per fuzzing process (libFuzzer's -jobs run several).
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "wb_fuzz_XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) std::abort();
    std::atexit([] { std::filesystem::remove_all(ScratchDir()); });
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

inline void WriteBytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) std::abort();
}

// An invariant of the code under test broke: a finding, like a crash.
inline void Require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "invariant violated: %s\n", what);
  std::abort();
}

inline void WriteSeedsIfAsked() {
  const char* dir = std::getenv("WB_FUZZ_WRITE_SEEDS");
  if (dir == nullptr) return;
  std::filesystem::create_directories(dir);
  const std::vector<std::string> seeds = Seeds();
  for (size_t i = 0; i < seeds.size(); ++i)
    WriteBytes(std::filesystem::path(dir) / ("seed" + std::to_string(i)), seeds[i]);
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  wavebake::fuzz::WriteSeedsIfAsked();
  return 0;
}
