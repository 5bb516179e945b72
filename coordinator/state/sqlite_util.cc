#include "coordinator/state/sqlite_util.h"

#include <algorithm>
#include <cerrno>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace wavebake {

namespace {

// What a message quotes of a statement: its start (a schema is kilobytes).
std::string Brief(absl::string_view sql) {
  while (!sql.empty() && (sql.front() == '\n' || sql.front() == ' ')) sql.remove_prefix(1);
  const size_t end = std::min(sql.find_first_of("\n("), size_t{48});
  return end < sql.size() ? absl::StrCat(sql.substr(0, end), "…") : std::string(sql);
}

// A full disk names the database file and says so; it is ResourceExhausted,
// like a full disk anywhere else (storage/files/atomic_file.h).
absl::Status ErrorOf(sqlite3* db, int rc, absl::string_view what, absl::string_view msg) {
  const char* file = db ? sqlite3_db_filename(db, "main") : nullptr;
  const std::string where = file && *file ? absl::StrCat(file, ": ") : "";
  // A write that failed for want of space is SQLITE_FULL, or SQLITE_IOERR
  // carrying ENOSPC (when the file itself could not grow).
  const bool full = (rc & 0xff) == SQLITE_FULL ||
                    ((rc & 0xff) == SQLITE_IOERR && db && sqlite3_system_errno(db) == ENOSPC);
  if (full)
    return absl::ResourceExhaustedError(
        absl::StrCat(where, "No space left on device (sqlite ", what, ": ", msg, ")"));
  return absl::InternalError(absl::StrCat(where, "sqlite: ", what, ": ", msg));
}

}  // namespace

absl::Status SqliteError(sqlite3* db, absl::string_view what) {
  if (!db) return absl::InternalError(absl::StrCat("sqlite: ", what, ": out of memory"));
  return ErrorOf(db, sqlite3_extended_errcode(db), what, sqlite3_errmsg(db));
}

absl::StatusOr<SqliteDb> OpenSqlite(const std::string& path, bool read_only) {
  sqlite3* raw = nullptr;
  // FULLMUTEX: the reader connection serves Watch streams on many threads.
  const int flags =
      (read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE) |
      SQLITE_OPEN_FULLMUTEX;
  const int rc = sqlite3_open_v2(path.c_str(), &raw, flags, nullptr);
  SqliteDb db(raw);
  if (rc != SQLITE_OK) return SqliteError(db.get(), absl::StrCat("open ", path));
  sqlite3_busy_timeout(db.get(), 5000);
  return db;
}

absl::Status ExecSql(sqlite3* db, const char* sql) {
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql, nullptr, nullptr, &err);
  if (rc == SQLITE_OK) return absl::OkStatus();
  std::string msg = err ? err : "unknown error";
  sqlite3_free(err);
  return ErrorOf(db, rc, Brief(sql), msg);
}

absl::StatusOr<SqliteStmt> PrepareSql(sqlite3* db, absl::string_view sql) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v3(db, sql.data(), static_cast<int>(sql.size()), SQLITE_PREPARE_PERSISTENT,
                         &raw, nullptr) != SQLITE_OK) {
    return SqliteError(db, absl::StrCat("prepare ", Brief(sql)));
  }
  return SqliteStmt(raw);
}

absl::StatusOr<SqliteTxn> SqliteTxn::Begin(sqlite3* db) {
  if (absl::Status s = ExecSql(db, "BEGIN IMMEDIATE"); !s.ok()) return s;
  return SqliteTxn(db);
}

SqliteTxn::~SqliteTxn() {
  if (db_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

absl::Status SqliteTxn::Commit() {
  absl::Status s = ExecSql(db_, "COMMIT");
  if (s.ok()) db_ = nullptr;
  return s;
}

SqliteCursor& SqliteCursor::Bind(int64_t v) {
  sqlite3_bind_int64(stmt_, next_++, v);
  return *this;
}

SqliteCursor& SqliteCursor::Bind(absl::string_view text) {
  sqlite3_bind_text(stmt_, next_++, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
  return *this;
}

SqliteCursor& SqliteCursor::BindBlob(absl::string_view bytes) {
  sqlite3_bind_blob(stmt_, next_++, bytes.data(), static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  return *this;
}

absl::StatusOr<bool> SqliteCursor::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  return SqliteError(sqlite3_db_handle(stmt_), Brief(sqlite3_sql(stmt_)));
}

absl::Status SqliteCursor::Run() {
  absl::StatusOr<bool> row = Step();
  return row.ok() ? absl::OkStatus() : row.status();
}

std::string SqliteCursor::Text(int col) const {
  const auto* p = static_cast<const char*>(sqlite3_column_blob(stmt_, col));
  const int n = sqlite3_column_bytes(stmt_, col);
  return p ? std::string(p, static_cast<size_t>(n)) : std::string();
}

}  // namespace wavebake
