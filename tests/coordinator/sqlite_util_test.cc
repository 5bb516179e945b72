// SQLite errors name the database file and stay short: a failed schema used
// to be quoted whole (kilobytes) before "database or disk is full".
#include "coordinator/state/sqlite_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

TEST(SqliteUtilTest, ErrorsNameTheFileAndQuoteOnlyTheStatementsStart) {
  testing::TempDir dir;
  const std::string path = (dir.path() / "state.sqlite").string();
  absl::StatusOr<SqliteDb> db = OpenSqlite(path, false);
  ASSERT_TRUE(db.ok()) << db.status();
  std::string sql = "\n  CREATE TABLE t (a INTEGER);\n";
  for (int i = 0; i < 200; ++i) sql += "CREATE TABLE t (a INTEGER);\n";  // the second fails
  const absl::Status s = ExecSql(db->get(), sql.c_str());
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(std::string(s.message()), HasSubstr(path + ": sqlite: CREATE TABLE t …"));
  EXPECT_THAT(std::string(s.message()), HasSubstr("already exists"));
  EXPECT_LT(s.message().size(), path.size() + 120) << s.message();
}

}  // namespace
}  // namespace wavebake
