#pragma once
// The samples/ arrays of a store (DESIGN.md §3): the W×H grid of sample ids
// and the per-sample position, normal, albedo (and mesh vertex id). FINALIZE
// writes them; ReadSamples (storage/store/store_reader.h) reads them back.
#include <filesystem>

#include "absl/status/status.h"
#include "core/layouts/samples.h"

namespace wavebake {

absl::Status WriteSamples(const std::filesystem::path& store, const SampleSet& samples);

}  // namespace wavebake
