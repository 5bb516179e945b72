#pragma once
// Helpers shared by the storage tests: a scratch directory and a way to run
// the independent reader (/usr/bin/python3 with zarr, DESIGN.md §3).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "tests/testing/scratch_dir.h"

namespace wavebake::testing {

using TempDir = test_support::ScratchDir;

// Names in `dir` (recursively, relative) that are temp files of AtomicWriteFile.
std::vector<std::string> PartialFiles(const std::filesystem::path& dir);

// Writes raw bytes with plain stdio, independent of the code under test.
void WriteRawFile(const std::filesystem::path& path, std::span<const std::byte> data);

struct ProcessResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};
// Runs `script` with /usr/bin/python3 (which has zarr and numcodecs); a
// missing interpreter is a non-zero exit code, never a skip.
ProcessResult RunPython(const std::filesystem::path& work_dir, const std::string& script);

}  // namespace wavebake::testing
