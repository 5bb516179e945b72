#pragma once
// RAII over the SQLite C API: handles in unique_ptr with deleters, a
// transaction that rolls back unless committed, and a cursor that binds by
// position and resets its (cached) statement when it goes out of scope.
#include <sqlite3.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace wavebake {

struct SqliteCloser {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
struct SqliteFinalizer {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using SqliteDb = std::unique_ptr<sqlite3, SqliteCloser>;
using SqliteStmt = std::unique_ptr<sqlite3_stmt, SqliteFinalizer>;

absl::Status SqliteError(sqlite3* db, absl::string_view what);
absl::StatusOr<SqliteDb> OpenSqlite(const std::string& path, bool read_only);
absl::Status ExecSql(sqlite3* db, const char* sql);
absl::StatusOr<SqliteStmt> PrepareSql(sqlite3* db, absl::string_view sql);

// BEGIN IMMEDIATE ... COMMIT; the destructor rolls back an uncommitted one, so
// an error half-way leaves the database as it was (§4: nothing half-written).
class SqliteTxn {
 public:
  static absl::StatusOr<SqliteTxn> Begin(sqlite3* db);
  SqliteTxn(SqliteTxn&& o) noexcept : db_(std::exchange(o.db_, nullptr)) {}
  SqliteTxn& operator=(SqliteTxn&&) = delete;
  ~SqliteTxn();
  absl::Status Commit();

 private:
  explicit SqliteTxn(sqlite3* db) : db_(db) {}
  sqlite3* db_;
};

class SqliteCursor {
 public:
  explicit SqliteCursor(sqlite3_stmt* stmt) : stmt_(stmt) {}
  SqliteCursor(const SqliteCursor&) = delete;
  SqliteCursor& operator=(const SqliteCursor&) = delete;
  ~SqliteCursor() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }

  SqliteCursor& Bind(int64_t v);
  SqliteCursor& Bind(int v) { return Bind(static_cast<int64_t>(v)); }
  SqliteCursor& Bind(bool v) { return Bind(static_cast<int64_t>(v)); }
  SqliteCursor& Bind(absl::string_view text);
  SqliteCursor& BindBlob(absl::string_view bytes);

  // true: a row is available; false: done.
  absl::StatusOr<bool> Step();
  // Runs a statement that returns no rows.
  absl::Status Run();

  int64_t Int(int col) const { return sqlite3_column_int64(stmt_, col); }
  std::string Text(int col) const;

 private:
  sqlite3_stmt* stmt_;
  int next_ = 1;
};

}  // namespace wavebake
