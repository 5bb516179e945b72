#pragma once
// How much memory this process may use: the machine's physical memory, or
// less where its cgroup caps it (a container's limit, a Slurm job step's
// --mem). Budgets that hold work in memory are fractions of it.
#include <cstdint>
#include <optional>
#include <string_view>

namespace wavebake::driver {

// The least of the physical memory and the memory limit of this process's
// cgroup (v2 memory.max, v1 memory.limit_in_bytes) where one is set.
uint64_t UsableMemoryBytes();

// A cgroup limit file's content in bytes; nullopt for "max" (no limit) or
// text that is not a number.
std::optional<uint64_t> ParseCgroupLimit(std::string_view text);

}  // namespace wavebake::driver
