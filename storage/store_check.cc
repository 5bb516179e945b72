#include "storage/store_check.h"

#include "absl/status/statusor.h"
#include "storage/store_reader.h"

namespace wavebake {

// The readers open every final array complete (ZarrArray::OpenComplete) and
// hold it to the manifest; reading them all is the check.
absl::Status CheckStoreComplete(const std::filesystem::path& store) {
  if (absl::StatusOr<SampleSet> samples = ReadSamples(store); !samples.ok())
    return samples.status();
  return ReadTransport(store).status();
}

}  // namespace wavebake
