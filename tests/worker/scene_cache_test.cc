// SceneCache: built-ins pass through, uploaded scenes are fetched once by
// content hash and reused, local scenes are used in place; the store always
// records a name every worker agrees on.
#include "worker/loop/scene_cache.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "storage/files/sha256.h"
#include "tests/worker/staging_testing.h"

namespace wavebake {
namespace {

using staging_testing::ScratchDir;

const std::string kSha(64, 'a');

v1::SceneSource Uploaded(const std::string& sha, const std::string& name, int64_t size) {
  v1::SceneSource s;
  s.mutable_uploaded()->set_sha256(sha);
  s.mutable_uploaded()->set_file_name(name);
  s.mutable_uploaded()->set_size(size);
  return s;
}

std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fake coordinator that serves `bytes` and counts the fetches.
struct FakeFetch {
  std::string bytes;
  int calls = 0;
  SceneCache::FetchFn Fn() {
    return [this](const v1::SceneRef&, const std::filesystem::path& dest) {
      ++calls;
      std::ofstream(dest, std::ios::binary) << bytes;
      return absl::OkStatus();
    };
  }
};

TEST(SceneCacheTest, BuiltinsNeedNoFetch) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  FakeFetch fetch;
  for (const char* name : {"builtin:furnace", "furnace"}) {
    v1::SceneSource s;
    s.set_builtin(name);
    absl::StatusOr<SceneSpec> spec = cache.Resolve(s, fetch.Fn());
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(spec->load, "builtin:furnace");
    EXPECT_EQ(spec->recorded, "builtin:furnace");
  }
  EXPECT_EQ(fetch.calls, 0);
}

TEST(SceneCacheTest, FetchesAnUploadOnceAndRecordsItsFileName) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  FakeFetch fetch{.bytes = "v 0 0 0\n"};
  const std::string sha = Sha256Hex(fetch.bytes);
  const v1::SceneSource s = Uploaded(sha, "models/tri.obj", 8);
  for (int i = 0; i < 3; ++i) {
    absl::StatusOr<SceneSpec> spec = cache.Resolve(s, fetch.Fn());
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(spec->load, (dir.path() / sha / "tri.obj").string());
    EXPECT_EQ(spec->recorded, "tri.obj");
    EXPECT_EQ(Read(spec->load), "v 0 0 0\n");
  }
  EXPECT_EQ(fetch.calls, 1);
  // Another worker process sharing the directory finds it too.
  SceneCache other(dir.path());
  ASSERT_TRUE(other.Resolve(s, fetch.Fn()).ok());
  EXPECT_EQ(fetch.calls, 1);
}

TEST(SceneCacheTest, ACachedFileOfTheWrongSizeIsFetchedAgain) {
  ScratchDir dir;
  FakeFetch fetch{.bytes = "v 0 0 0\nv 1 0 0\n"};
  const std::string sha = Sha256Hex(fetch.bytes);
  std::filesystem::create_directories(dir.path() / sha);
  std::ofstream(dir.path() / sha / "tri.obj") << "truncated";
  SceneCache cache(dir.path());
  absl::StatusOr<SceneSpec> spec = cache.Resolve(Uploaded(sha, "tri.obj", 16), fetch.Fn());
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(fetch.calls, 1);
  EXPECT_EQ(Read(spec->load), fetch.bytes);
}

TEST(SceneCacheTest, AFailedFetchLeavesNothing) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  const SceneCache::FetchFn broken = [](const v1::SceneRef&, const std::filesystem::path& dest) {
    std::ofstream(dest) << "half";
    return absl::UnavailableError("coordinator went away");
  };
  absl::StatusOr<SceneSpec> spec = cache.Resolve(Uploaded(kSha, "tri.obj", 100), broken);
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path() / kSha));
}

// A coordinator (or a network) that serves other bytes than the hash names
// must not get them loaded and recorded under that hash.
TEST(SceneCacheTest, BytesThatDoNotHashToTheirNameAreRefusedAndNotCached) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  FakeFetch fetch{.bytes = "v 0 0 0\n"};
  const std::string other = Sha256Hex("v 9 9 9\n");
  absl::StatusOr<SceneSpec> spec = cache.Resolve(Uploaded(other, "tri.obj", 8), fetch.Fn());
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(std::string(spec.status().message()), testing::HasSubstr(Sha256Hex(fetch.bytes)));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path() / other));
  // The next task tries again rather than trusting a bad cache entry.
  EXPECT_FALSE(cache.Resolve(Uploaded(other, "tri.obj", 8), fetch.Fn()).ok());
  EXPECT_EQ(fetch.calls, 2);
}

// A worker loads an uploaded scene as the coordinator planned it: reading
// only what was uploaded (storage/scene_files/scene_files.h), not its own disk.
TEST(SceneCacheTest, UploadedScenesReadOnlyTheirUpload) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  const std::filesystem::path server_mesh = dir.path() / "server.obj";
  std::ofstream(server_mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  // A JSON scene naming a file of this host, absolutely or by "..", is
  // refused before anything is loaded, naming the field.
  for (const std::string& reference : {server_mesh.string(), std::string("../../server.obj")}) {
    FakeFetch fetch{.bytes = R"({"meshes": [{"file": ")" + reference + R"("}]})"};
    absl::StatusOr<SceneSpec> spec =
        cache.Resolve(Uploaded(Sha256Hex(fetch.bytes), "evil.json", 0), fetch.Fn());
    ASSERT_FALSE(spec.ok()) << reference;
    EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(std::string(spec.status().message()), testing::HasSubstr("meshes[0].file"))
        << spec.status();
  }
  // Any other upload loads through files confined to its own directory.
  FakeFetch fetch{.bytes = "mtllib ../../server.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"};
  absl::StatusOr<SceneSpec> spec =
      cache.Resolve(Uploaded(Sha256Hex(fetch.bytes), "m.obj", 0), fetch.Fn());
  ASSERT_TRUE(spec.ok()) << spec.status();
  ASSERT_NE(spec->files, nullptr);
  std::string warning;
  EXPECT_EQ(spec->files->Resolve(spec->load, server_mesh.string(), &warning).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_FALSE(spec->files->Open(server_mesh).has_value());
  EXPECT_TRUE(spec->files->Open(spec->load).has_value());
}

TEST(SceneCacheTest, LocalScenesAreUsedInPlace) {
  ScratchDir dir;
  SceneCache cache(dir.path(), {{kSha, "scenes/room.json"}});
  FakeFetch fetch;
  absl::StatusOr<SceneSpec> spec = cache.Resolve(Uploaded(kSha, "room.json", 10), fetch.Fn());
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->load, "scenes/room.json");
  EXPECT_EQ(spec->recorded, "room.json");  // its name, not where this machine keeps it
  EXPECT_EQ(fetch.calls, 0);
}

TEST(SceneCacheTest, RefusesWhatIsNotAHash) {
  ScratchDir dir;
  SceneCache cache(dir.path());
  FakeFetch fetch;
  absl::StatusOr<SceneSpec> spec = cache.Resolve(Uploaded("../../etc", "x.obj", 1), fetch.Fn());
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(fetch.calls, 0);
}

}  // namespace
}  // namespace wavebake
