#include "coordinator/state/job_store.h"

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

// user_version 1. Enum columns hold the wavebake.v1 enum numbers.
constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS jobs(
  id INTEGER PRIMARY KEY, request BLOB NOT NULL, phase INTEGER NOT NULL,
  tiles INTEGER NOT NULL, groups_count INTEGER NOT NULL, rays_estimate INTEGER NOT NULL,
  store_path TEXT NOT NULL, max_attempts INTEGER NOT NULL, error TEXT NOT NULL,
  stats_json TEXT NOT NULL, rays_traced INTEGER NOT NULL, bytes_written INTEGER NOT NULL,
  created_ms INTEGER NOT NULL, started_ms INTEGER NOT NULL, finished_ms INTEGER NOT NULL,
  cleaned INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS tasks(
  job_id INTEGER NOT NULL, idx INTEGER NOT NULL, kind INTEGER NOT NULL,
  kind_index INTEGER NOT NULL, state INTEGER NOT NULL, attempts INTEGER NOT NULL,
  failures INTEGER NOT NULL, worker_id TEXT NOT NULL, last_error TEXT NOT NULL,
  rays_traced INTEGER NOT NULL, bytes_written INTEGER NOT NULL, stats_json TEXT NOT NULL,
  PRIMARY KEY(job_id, idx)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS events(
  job_id INTEGER NOT NULL, seq INTEGER NOT NULL, unix_ms INTEGER NOT NULL,
  kind INTEGER NOT NULL, phase INTEGER NOT NULL, task_kind INTEGER NOT NULL,
  task_index INTEGER NOT NULL, worker_id TEXT NOT NULL, message TEXT NOT NULL,
  tasks_done INTEGER NOT NULL, tasks_total INTEGER NOT NULL, rays_traced INTEGER NOT NULL,
  bytes_written INTEGER NOT NULL, stats_json TEXT NOT NULL,
  PRIMARY KEY(job_id, seq)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS workers(
  id INTEGER PRIMARY KEY, name TEXT NOT NULL, threads INTEGER NOT NULL,
  registered_ms INTEGER NOT NULL, consecutive_failures INTEGER NOT NULL,
  excluded INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS scenes(
  sha256 TEXT PRIMARY KEY, size INTEGER NOT NULL, file_name TEXT NOT NULL,
  created_ms INTEGER NOT NULL);
PRAGMA user_version = 1;
)sql";

constexpr const char* kJobColumns =
    "id, request, phase, tiles, groups_count, rays_estimate, store_path, max_attempts, error, "
    "stats_json, rays_traced, bytes_written, created_ms, started_ms, finished_ms, cleaned";
constexpr const char* kTaskColumns =
    "job_id, idx, kind, kind_index, state, attempts, failures, worker_id, last_error, "
    "rays_traced, bytes_written, stats_json";
constexpr const char* kEventColumns =
    "job_id, seq, unix_ms, kind, phase, task_kind, task_index, worker_id, message, tasks_done, "
    "tasks_total, rays_traced, bytes_written, stats_json";

JobRecord JobFromRow(const SqliteCursor& c) {
  JobRecord j;
  j.id = c.Int(0);
  j.request = c.Text(1);
  j.phase = static_cast<Phase>(c.Int(2));
  j.tiles = static_cast<int>(c.Int(3));
  j.groups = static_cast<int>(c.Int(4));
  j.rays_estimate = c.Int(5);
  j.store_path = c.Text(6);
  j.max_attempts = static_cast<int>(c.Int(7));
  j.error = c.Text(8);
  j.stats_json = c.Text(9);
  j.rays_traced = c.Int(10);
  j.bytes_written = c.Int(11);
  j.created_ms = c.Int(12);
  j.started_ms = c.Int(13);
  j.finished_ms = c.Int(14);
  j.cleaned = c.Int(15) != 0;
  return j;
}

TaskRecord TaskFromRow(const SqliteCursor& c) {
  TaskRecord t;
  t.job_id = c.Int(0);
  t.index = static_cast<int>(c.Int(1));
  t.kind = static_cast<TaskKind>(c.Int(2));
  t.kind_index = static_cast<int>(c.Int(3));
  t.state = static_cast<TaskState>(c.Int(4));
  t.attempts = static_cast<int>(c.Int(5));
  t.failures = static_cast<int>(c.Int(6));
  t.worker_id = c.Text(7);
  t.last_error = c.Text(8);
  t.rays_traced = c.Int(9);
  t.bytes_written = c.Int(10);
  t.stats_json = c.Text(11);
  return t;
}

EventRecord EventFromRow(const SqliteCursor& c) {
  EventRecord e;
  e.job_id = c.Int(0);
  e.seq = c.Int(1);
  e.unix_ms = c.Int(2);
  e.kind = static_cast<EventKind>(c.Int(3));
  e.phase = static_cast<Phase>(c.Int(4));
  e.task_kind = static_cast<TaskKind>(c.Int(5));
  e.task_index = static_cast<int>(c.Int(6));
  e.worker_id = c.Text(7);
  e.message = c.Text(8);
  e.tasks_done = static_cast<int>(c.Int(9));
  e.tasks_total = static_cast<int>(c.Int(10));
  e.rays_traced = c.Int(11);
  e.bytes_written = c.Int(12);
  e.stats_json = c.Text(13);
  return e;
}

// Runs `sql` (no parameters) and calls `row` for every result row.
template <typename F>
absl::Status ForEachRow(sqlite3* db, const std::string& sql, F row) {
  absl::StatusOr<SqliteStmt> stmt = PrepareSql(db, sql);
  if (!stmt.ok()) return stmt.status();
  SqliteCursor c(stmt->get());
  for (;;) {
    absl::StatusOr<bool> more = c.Step();
    if (!more.ok()) return more.status();
    if (!*more) return absl::OkStatus();
    row(c);
  }
}

}  // namespace

absl::StatusOr<std::unique_ptr<JobStore>> JobStore::Open(const std::string& path) {
  auto store = std::make_unique<JobStore>(Key{});
  if (absl::Status s = store->Init(path); !s.ok()) return s;
  return store;
}

absl::Status JobStore::Init(const std::string& path) {
  absl::StatusOr<SqliteDb> db = OpenSqlite(path, /*read_only=*/false);
  if (!db.ok()) return db.status();
  writer_ = std::move(*db);
  // WAL: readers (Watch) never block the writer. synchronous=NORMAL is
  // durable against a crash of the coordinator (the WAL is fsynced at
  // checkpoints); a power cut may lose the last transitions, which only
  // re-runs deterministic tasks (DESIGN.md §1 determinism).
  for (const char* pragma : {"PRAGMA journal_mode=WAL", "PRAGMA synchronous=NORMAL"}) {
    if (absl::Status s = ExecSql(writer_.get(), pragma); !s.ok()) return s;
  }
  if (absl::Status s = ExecSql(writer_.get(), kSchema); !s.ok()) return s;
  if (path != ":memory:" && !path.empty()) {
    absl::StatusOr<SqliteDb> r = OpenSqlite(path, /*read_only=*/true);
    if (!r.ok()) return r.status();
    reader_ = std::move(*r);
    if (absl::Status s = StartCheckpointer(path); !s.ok()) return s;
  }
  struct {
    SqliteStmt* stmt;
    std::string sql;
  } const prepared[] = {
      {&upsert_job_, absl::StrCat("INSERT OR REPLACE INTO jobs(", kJobColumns,
                                  ") VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)")},
      {&upsert_task_, absl::StrCat("INSERT OR REPLACE INTO tasks(", kTaskColumns,
                                   ") VALUES(?,?,?,?,?,?,?,?,?,?,?,?)")},
      {&insert_event_,
       absl::StrCat("INSERT INTO events(", kEventColumns, ") VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?)")},
      {&upsert_worker_,
       "INSERT OR REPLACE INTO workers(id, name, threads, registered_ms, consecutive_failures, "
       "excluded) VALUES(?,?,?,?,?,?)"},
  };
  for (const auto& p : prepared) {
    absl::StatusOr<SqliteStmt> stmt = PrepareSql(writer_.get(), p.sql);
    if (!stmt.ok()) return stmt.status();
    *p.stmt = std::move(*stmt);
  }
  return absl::OkStatus();
}

// Past this many WAL pages the checkpointer is woken; past kWalHardPages the
// committing connection checkpoints itself (the background one is stuck).
constexpr int kWalCheckpointPages = 1000;
constexpr int kWalHardPages = 64000;

absl::Status JobStore::StartCheckpointer(const std::string& path) {
  absl::StatusOr<SqliteDb> db = OpenSqlite(path, /*read_only=*/false);
  if (!db.ok()) return db.status();
  checkpointer_ = std::move(*db);
  if (absl::Status s = ExecSql(writer_.get(), "PRAGMA wal_autocheckpoint=0"); !s.ok()) return s;
  sqlite3_wal_hook(writer_.get(), &JobStore::OnWalCommit, this);
  checkpoint_thread_ = std::jthread([this](std::stop_token stop) { CheckpointLoop(stop); });
  return absl::OkStatus();
}

int JobStore::OnWalCommit(void* self, sqlite3* db, const char*, int pages) {
  auto* store = static_cast<JobStore*>(self);
  if (pages >= kWalHardPages) {
    sqlite3_wal_checkpoint_v2(db, nullptr, SQLITE_CHECKPOINT_PASSIVE, nullptr, nullptr);
  } else if (pages >= kWalCheckpointPages) {
    {
      std::lock_guard lock(store->checkpoint_mu_);
      store->checkpoint_due_ = true;
    }
    store->checkpoint_cv_.notify_one();
  }
  return SQLITE_OK;
}

void JobStore::CheckpointLoop(std::stop_token stop) {
  for (;;) {
    {
      std::unique_lock lock(checkpoint_mu_);
      checkpoint_cv_.wait_for(lock, stop, std::chrono::seconds(1),
                              [this] { return checkpoint_due_; });
      if (stop.stop_requested()) return;
      checkpoint_due_ = false;
    }
    // PASSIVE: copies what it can without blocking the writer or readers.
    sqlite3_wal_checkpoint_v2(checkpointer_.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, nullptr,
                              nullptr);
  }
}

absl::Status JobStore::UpsertJob(const JobRecord& j) {
  SqliteCursor c(upsert_job_.get());
  c.Bind(j.id).BindBlob(j.request).Bind(static_cast<int>(j.phase)).Bind(j.tiles).Bind(j.groups);
  c.Bind(j.rays_estimate).Bind(j.store_path).Bind(j.max_attempts).Bind(j.error);
  c.Bind(j.stats_json).Bind(j.rays_traced).Bind(j.bytes_written).Bind(j.created_ms);
  c.Bind(j.started_ms).Bind(j.finished_ms).Bind(j.cleaned);
  return c.Run();
}

absl::Status JobStore::UpsertTask(const TaskRecord& t) {
  SqliteCursor c(upsert_task_.get());
  c.Bind(t.job_id).Bind(t.index).Bind(static_cast<int>(t.kind)).Bind(t.kind_index);
  c.Bind(static_cast<int>(t.state)).Bind(t.attempts).Bind(t.failures).Bind(t.worker_id);
  c.Bind(t.last_error).Bind(t.rays_traced).Bind(t.bytes_written).Bind(t.stats_json);
  return c.Run();
}

absl::Status JobStore::InsertEvent(const EventRecord& e) {
  SqliteCursor c(insert_event_.get());
  c.Bind(e.job_id).Bind(e.seq).Bind(e.unix_ms).Bind(static_cast<int>(e.kind));
  c.Bind(static_cast<int>(e.phase)).Bind(static_cast<int>(e.task_kind)).Bind(e.task_index);
  c.Bind(e.worker_id).Bind(e.message).Bind(e.tasks_done).Bind(e.tasks_total);
  c.Bind(e.rays_traced).Bind(e.bytes_written).Bind(e.stats_json);
  return c.Run();
}

absl::Status JobStore::UpsertWorker(const WorkerRecord& w) {
  SqliteCursor c(upsert_worker_.get());
  c.Bind(w.id).Bind(w.name).Bind(w.threads).Bind(w.registered_ms);
  c.Bind(w.consecutive_failures).Bind(w.excluded);
  return c.Run();
}

absl::Status JobStore::Commit(const Transition& t) {
  std::lock_guard lock(write_mu_);
  if (full_for_testing_) {
    return absl::ResourceExhaustedError("state.sqlite: No space left on device (injected)");
  }
  absl::StatusOr<SqliteTxn> txn = SqliteTxn::Begin(writer_.get());
  if (!txn.ok()) return txn.status();
  for (const JobRecord& j : t.jobs) {
    if (absl::Status s = UpsertJob(j); !s.ok()) return s;
  }
  for (const TaskRecord& task : t.tasks) {
    if (absl::Status s = UpsertTask(task); !s.ok()) return s;
  }
  for (const EventRecord& e : t.events) {
    if (absl::Status s = InsertEvent(e); !s.ok()) return s;
  }
  for (const WorkerRecord& w : t.workers) {
    if (absl::Status s = UpsertWorker(w); !s.ok()) return s;
  }
  return txn->Commit();
}

absl::StatusOr<StoreSnapshot> JobStore::Load() {
  std::lock_guard lock(write_mu_);
  StoreSnapshot snap;
  sqlite3* db = writer_.get();
  absl::Status s = ForEachRow(db, absl::StrCat("SELECT ", kJobColumns, " FROM jobs ORDER BY id"),
                              [&](const SqliteCursor& c) { snap.jobs.push_back(JobFromRow(c)); });
  if (!s.ok()) return s;
  s = ForEachRow(db,
                 absl::StrCat("SELECT ", kTaskColumns,
                              " FROM tasks WHERE job_id IN (SELECT id FROM jobs WHERE phase < ",
                              static_cast<int>(Phase::kDone), ") ORDER BY job_id, idx"),
                 [&](const SqliteCursor& c) { snap.tasks.push_back(TaskFromRow(c)); });
  if (!s.ok()) return s;
  s = ForEachRow(db,
                 "SELECT id, name, threads, registered_ms, consecutive_failures, excluded "
                 "FROM workers ORDER BY id",
                 [&](const SqliteCursor& c) {
                   snap.workers.push_back({.id = c.Int(0),
                                           .name = c.Text(1),
                                           .threads = static_cast<int>(c.Int(2)),
                                           .registered_ms = c.Int(3),
                                           .consecutive_failures = static_cast<int>(c.Int(4)),
                                           .excluded = c.Int(5) != 0});
                 });
  if (!s.ok()) return s;
  s = ForEachRow(db, "SELECT job_id, MAX(seq) FROM events GROUP BY job_id",
                 [&](const SqliteCursor& c) { snap.last_event_seq[c.Int(0)] = c.Int(1); });
  if (!s.ok()) return s;
  return snap;
}

absl::StatusOr<std::vector<EventRecord>> JobStore::ReadEvents(int64_t job_id, int64_t after_seq,
                                                              int limit) {
  std::lock_guard lock(reader_mu());
  std::vector<EventRecord> out;
  absl::Status s =
      ForEachRow(reader(),
                 absl::StrCat("SELECT ", kEventColumns, " FROM events WHERE job_id = ", job_id,
                              " AND seq > ", after_seq, " ORDER BY seq LIMIT ", limit),
                 [&](const SqliteCursor& c) { out.push_back(EventFromRow(c)); });
  if (!s.ok()) return s;
  return out;
}

absl::StatusOr<std::vector<TaskRecord>> JobStore::ReadTasks(int64_t job_id) {
  std::lock_guard lock(reader_mu());
  std::vector<TaskRecord> out;
  absl::Status s = ForEachRow(
      reader(),
      absl::StrCat("SELECT ", kTaskColumns, " FROM tasks WHERE job_id = ", job_id, " ORDER BY idx"),
      [&](const SqliteCursor& c) { out.push_back(TaskFromRow(c)); });
  if (!s.ok()) return s;
  return out;
}

absl::Status JobStore::LimitGrowthForTesting(int64_t pages) {
  std::lock_guard lock(write_mu_);
  int64_t count = 0;
  absl::Status s = ForEachRow(writer_.get(), "PRAGMA page_count",
                              [&](const SqliteCursor& c) { count = c.Int(0); });
  if (!s.ok()) return s;
  return ForEachRow(writer_.get(), absl::StrCat("PRAGMA max_page_count = ", count + pages),
                    [](const SqliteCursor&) {});
}

absl::Status JobStore::PutScene(const SceneRecord& scene) {
  std::lock_guard lock(write_mu_);
  absl::StatusOr<SqliteStmt> stmt = PrepareSql(
      writer_.get(),
      "INSERT OR IGNORE INTO scenes(sha256, size, file_name, created_ms) VALUES(?,?,?,?)");
  if (!stmt.ok()) return stmt.status();
  SqliteCursor c(stmt->get());
  c.Bind(scene.sha256).Bind(scene.size).Bind(scene.file_name).Bind(scene.created_ms);
  return c.Run();
}

absl::StatusOr<std::optional<SceneRecord>> JobStore::GetScene(const std::string& sha256) {
  std::lock_guard lock(reader_mu());
  absl::StatusOr<SqliteStmt> stmt = PrepareSql(
      reader(), "SELECT sha256, size, file_name, created_ms FROM scenes WHERE sha256 = ?");
  if (!stmt.ok()) return stmt.status();
  SqliteCursor c(stmt->get());
  c.Bind(sha256);
  absl::StatusOr<bool> row = c.Step();
  if (!row.ok()) return row.status();
  if (!*row) return std::nullopt;
  return SceneRecord{c.Text(0), c.Int(1), c.Text(2), c.Int(3)};
}

}  // namespace wavebake
