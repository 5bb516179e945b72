// The relight view's probes: the built-ins and the .hdr/.exr files under
// --probes, by relative name; any other name — a path, a file outside the
// list, a traversal — is refused, so a client never names a server file.
#include "web/views/probe_catalogue.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "tests/testing/scratch_dir.h"

namespace wavebake::web {
namespace {

using ::testing::ElementsAre;

TEST(ProbeCatalogueTest, BuiltinsThenFilesByRelativeName) {
  test_support::ScratchDir dir("probes");
  std::filesystem::create_directories(dir.path() / "indoor");
  for (const char* f : {"b.hdr", "indoor/a.EXR", "notes.txt", "indoor/c.png"}) {
    std::ofstream(dir.path() / f) << "x";
  }
  absl::StatusOr<ProbeCatalogue> c = ProbeCatalogue::Scan(dir.path());
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_THAT(c->names(), ElementsAre("builtin:sky", "builtin:constant", "b.hdr", "indoor/a.EXR"));
  EXPECT_EQ(*c->Spec("b.hdr"), (std::filesystem::absolute(dir.path()) / "b.hdr").string());
  EXPECT_EQ(*c->Spec("builtin:sky"), "builtin:sky");
  const std::vector<std::string> bad_names = {"notes.txt",
                                              "../b.hdr",
                                              "indoor/../b.hdr",
                                              "/etc/passwd",
                                              (dir.path() / "b.hdr").string(),
                                              "builtin:nothing",
                                              ""};
  for (const std::string& bad : bad_names) {
    EXPECT_EQ(c->Spec(bad).status().code(), absl::StatusCode::kNotFound) << bad;
  }
}

TEST(ProbeCatalogueTest, AMissingDirectoryIsNamed) {
  absl::StatusOr<ProbeCatalogue> c = ProbeCatalogue::Scan("/no/such/dir");
  ASSERT_FALSE(c.ok());
  EXPECT_THAT(c.status().message(), ::testing::HasSubstr("--probes: /no/such/dir"));
  EXPECT_THAT(ProbeCatalogue().names(), ElementsAre("builtin:sky", "builtin:constant"));
}

}  // namespace
}  // namespace wavebake::web
