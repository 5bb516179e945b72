// Worker failure reasons lose the worker's paths before they are stored.
#include "coordinator/service/worker_paths.h"

#include <gtest/gtest.h>

namespace wavebake {
namespace {

TEST(WorkerPathsTest, PathThroughTheStoreKeepsThePartFromTheStoreOn) {
  EXPECT_EQ(HideWorkerPaths("cannot write /mnt/w/store/.job-1.wbk.partial/staging/transport/0.5: "
                            "No space left on device",
                            "job-1.wbk"),
            "cannot write <store root>/.job-1.wbk.partial/staging/transport/0.5: "
            "No space left on device");
  // A relative --store-root, a published store, a store in a subdirectory.
  EXPECT_EQ(HideWorkerPaths("open 'data/store/job-1.wbk/.zattrs'", "job-1.wbk"),
            "open '<store root>/job-1.wbk/.zattrs'");
  EXPECT_EQ(HideWorkerPaths("(/x/y/a/.b.wbk.partial)", "a/b.wbk"),
            "(<store root>/a/.b.wbk.partial)");
}

TEST(WorkerPathsTest, OtherAbsolutePathsKeepTheirFileName) {
  EXPECT_EQ(HideWorkerPaths("scene /var/cache/wb/scenes/abc.obj: bad face", "job-1.wbk"),
            "scene <worker>/abc.obj: bad face");
  // A component that only resembles the store is not the store.
  EXPECT_EQ(HideWorkerPaths("/r/xjob-1.wbk/0", "job-1.wbk"), "<worker>/0");
}

TEST(WorkerPathsTest, LeavesEverythingElse) {
  for (const char* text :
       {"worker 3: lease expired", "transport/0.5 is short", "1/2 done", "/", "ratio 3/4", ""}) {
    EXPECT_EQ(HideWorkerPaths(text, "job-1.wbk"), text);
  }
}

}  // namespace
}  // namespace wavebake
