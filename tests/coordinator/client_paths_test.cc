// ClientPaths: the data directory and store root never reach a client, in
// any of the spellings a message may use; other text is left alone.
#include "coordinator/service/client_paths.h"

#include <gtest/gtest.h>

namespace wavebake {
namespace {

TEST(ClientPathsTest, HidesTheDirectoriesInEverySpelling) {
  ClientPaths paths;
  paths.Hide("/srv/wb/data", "<data dir>");
  paths.Hide("/srv/wb/data/store/", "<store root>");
  EXPECT_EQ(paths("cannot write /srv/wb/data/store/a.wbk.partial/x: No space left on device"),
            "cannot write <store root>/a.wbk.partial/x: No space left on device");
  EXPECT_EQ(paths("scene link /srv/wb/data/scene-names/ab/x.obj: denied"),
            "scene link <data dir>/scene-names/ab/x.obj: denied");
  EXPECT_EQ(paths("/srv/wb/data//store/../store/x"), "<data dir>//store/../store/x")
      << "an unnormalized spelling still loses the data dir";
  EXPECT_EQ(paths("output_name: \"a.wbk\" already exists"),
            "output_name: \"a.wbk\" already exists");
}

TEST(ClientPathsTest, RelativeDirectoriesAreHiddenByTheirAbsolutePath) {
  ClientPaths paths;
  paths.Hide("data", "<data dir>");
  const std::string absolute = std::filesystem::absolute("data").string();
  EXPECT_EQ(paths("open " + absolute + "/state.sqlite"), "open <data dir>/state.sqlite");
  EXPECT_EQ(paths("metadata"), "metadata") << "not inside words";
}

TEST(ClientPathsTest, NothingHiddenLeavesMessagesAsTheyAre) {
  EXPECT_EQ(ClientPaths()("/etc/passwd"), "/etc/passwd");
}

}  // namespace
}  // namespace wavebake
