// Partial stores of no unfinished job are removed at start; nothing else is.
#include "coordinator/state/orphan_stores.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

TEST(OrphanStoresTest, RemovesOnlyPartialStoresOfNoLiveJob) {
  testing::TempDir dir;
  const std::filesystem::path root = dir.path();
  for (const char* d : {".job-1.wbk.partial/staging", ".job-2.wbk.partial/staging", "job-3.wbk",
                        ".staging", "..x.partial"})
    std::filesystem::create_directories(root / d);
  std::ofstream(root / ".job-2.wbk.partial/staging/0.0") << "bytes";
  std::ofstream(root / ".zgroup.1.00000000deadbeef.partial") << "a temp file, not a store";
  std::ofstream(root / ".wavebake-store-root") << "id\n";

  absl::StatusOr<int> removed = RemoveOrphanPartialStores(root, {"job-1.wbk"});
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(*removed, 1);
  EXPECT_FALSE(std::filesystem::exists(root / ".job-2.wbk.partial"));
  for (const char* kept : {".job-1.wbk.partial/staging", "job-3.wbk", ".staging", "..x.partial",
                           ".zgroup.1.00000000deadbeef.partial", ".wavebake-store-root"})
    EXPECT_TRUE(std::filesystem::exists(root / kept)) << kept;
}

}  // namespace
}  // namespace wavebake
