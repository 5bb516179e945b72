// Lease throughput of the coordinator (DESIGN.md §4): simulated workers
// (threads) lease and complete trivial BAKE_TILE tasks. Counters of the
// baselines count single transactions (p99 in p99_lease_us). One "lease op" is a
// Lease followed by its Complete, i.e. two state transitions = two SQLite
// transactions. Target: >= 5,000 lease ops/s with the SQLite store.
//
// Rows, each with the same counters (lease_ops_per_s, p50/p99 of Lease and
// Complete in microseconds):
//   BM_SqliteTxn          baseline: a bare SQLite WAL transaction (UPDATE a
//                         row + INSERT an event) with SQLite's default inline
//                         checkpoints (an fsync every ~1000 pages)
//   BM_JobStoreCommit     baseline: one JobStore transition (task row + event),
//                         checkpoints in the background; a lease op costs two
//   BM_LeaseTableMemory   LeaseTable alone, no database
//   BM_LeaseTableSqlite   LeaseTable + JobStore (what the coordinator runs)
//   BM_GrpcLoopback       the real WorkerService over 127.0.0.1 (Lease + Complete)
//   BM_LeaseTableBatch    in-process baseline of the next row: LeaseTable +
//                         JobStore, each simulated worker calls Exchange
//                         (its T results + up to T new leases, one commit)
//   BM_GrpcBatch          the same over gRPC (LeaseBatch), every simulated
//                         worker on its own connection; vs_in_process is its
//                         rate over BM_LeaseTableBatch's with the same args
//   BM_GrpcHeartbeat      Heartbeat calls/s, each renewing T leases
//
// Args of the batch rows: {simulated workers, rounds per worker, T = threads
// per worker}; a round is one call that reports T tasks and leases T more.
//   build/bench_lease_throughput --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <grpcpp/grpcpp.h>
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <thread>
#include <vector>

#include "coordinator/scheduling/lease_table.h"
#include "coordinator/service/coordinator.h"
#include "coordinator/state/sqlite_util.h"
#include "wavebake.grpc.pb.h"

namespace wavebake {
namespace {

using Clock = std::chrono::steady_clock;

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "wb_bench_XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

double Micros(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

double Percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * v.size()));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

struct Latencies {
  std::vector<double> lease, complete;
};

// Runs `threads` simulated workers, each doing `ops` lease+complete cycles via
// `cycle(thread, &latencies)`; reports the counters and the wall time.
void RunWorkers(benchmark::State& state, int threads, int ops,
                const std::function<void(int, Latencies&)>& cycle) {
  std::vector<Latencies> lat(threads);
  const auto start = Clock::now();
  {
    std::vector<std::jthread> pool;
    for (int t = 0; t < threads; ++t) {
      pool.emplace_back([&, t] {
        for (int i = 0; i < ops; ++i) cycle(t, lat[t]);
      });
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  state.SetIterationTime(seconds);
  Latencies all;
  for (Latencies& l : lat) {
    all.lease.insert(all.lease.end(), l.lease.begin(), l.lease.end());
    all.complete.insert(all.complete.end(), l.complete.begin(), l.complete.end());
  }
  state.counters["lease_ops_per_s"] = threads * ops / seconds;
  state.counters["p50_lease_us"] = Percentile(all.lease, 0.50);
  state.counters["p99_lease_us"] = Percentile(all.lease, 0.99);
  state.counters["p99_complete_us"] = Percentile(all.complete, 0.99);
}

// One job with enough tiles for every cycle of every worker.
void LeaseAndComplete(benchmark::State& state, JobStore* store) {
  const int threads = static_cast<int>(state.range(0));
  const int ops = static_cast<int>(state.range(1));
  for (auto _ : state) {
    auto table = LeaseTable::Create(store, nullptr, {.lease_ms = 60'000}, nullptr);
    const int64_t job = (*table)->ReserveJobId();
    PlannedJob plan{
        .tiles = threads * ops + 1, .groups = 1, .store_path = "bench" + std::to_string(job)};
    if (!(*table)->AddJob(job, "", 3, plan).ok()) return state.SkipWithError("AddJob failed");
    std::vector<int64_t> workers;
    for (int t = 0; t < threads; ++t) workers.push_back(*(*table)->RegisterWorker("bench", 1));
    RunWorkers(state, threads, ops, [&](int t, Latencies& lat) {
      const auto t0 = Clock::now();
      auto grant = (*table)->Lease(workers[t]);
      const auto t1 = Clock::now();
      if (grant.ok() && grant->has_value()) (void)(*table)->Complete(workers[t], (*grant)->key, {});
      lat.lease.push_back(Micros(t1 - t0));
      lat.complete.push_back(Micros(Clock::now() - t1));
    });
  }
}

void BM_LeaseTableMemory(benchmark::State& state) { LeaseAndComplete(state, nullptr); }

void BM_LeaseTableSqlite(benchmark::State& state) {
  TempDir dir;
  auto store = JobStore::Open((dir.path() / "state.sqlite").string());
  if (!store.ok()) return state.SkipWithError("cannot open store");
  LeaseAndComplete(state, store->get());
}

// Baseline: the same kind of transaction as one transition, without any
// scheduling; two of them bound a lease op from above.
void BM_SqliteTxn(benchmark::State& state) {
  TempDir dir;
  auto db = OpenSqlite((dir.path() / "b.sqlite").string(), false);
  for (const char* sql : {"PRAGMA journal_mode=WAL", "PRAGMA synchronous=NORMAL",
                          "CREATE TABLE t(id INTEGER PRIMARY KEY, v INTEGER)",
                          "CREATE TABLE e(id INTEGER PRIMARY KEY, v INTEGER, s TEXT)",
                          "INSERT INTO t VALUES(1, 0)"}) {
    if (!ExecSql(db->get(), sql).ok()) return state.SkipWithError(sql);
  }
  auto update = PrepareSql(db->get(), "UPDATE t SET v = v + 1 WHERE id = 1");
  auto insert = PrepareSql(db->get(), "INSERT INTO e(v, s) VALUES(?, 'event')");
  const int ops = static_cast<int>(state.range(1));
  for (auto _ : state) {
    RunWorkers(state, 1, ops, [&](int, Latencies& lat) {
      const auto t0 = Clock::now();
      auto txn = SqliteTxn::Begin(db->get());
      (void)SqliteCursor(update->get()).Run();
      (void)SqliteCursor(insert->get()).Bind(int64_t{1}).Run();
      (void)txn->Commit();
      lat.lease.push_back(Micros(Clock::now() - t0));
    });
  }
}

// Baseline: the JobStore commit of one transition (a task row and an event),
// without scheduling; a lease op is two of these.
void BM_JobStoreCommit(benchmark::State& state) {
  TempDir dir;
  auto store = JobStore::Open((dir.path() / "state.sqlite").string());
  if (!store.ok()) return state.SkipWithError("cannot open store");
  const int ops = static_cast<int>(state.range(1));
  for (auto _ : state) {
    RunWorkers(state, 1, ops, [&](int, Latencies& lat) {
      static int64_t seq = 0;
      Transition tx;
      tx.tasks.push_back({.job_id = 1, .index = static_cast<int>(seq % 1000), .worker_id = "1"});
      tx.events.push_back({.job_id = 1, .seq = ++seq, .kind = EventKind::kTaskDone});
      const auto t0 = Clock::now();
      (void)(*store)->Commit(tx);
      lat.lease.push_back(Micros(Clock::now() - t0));
    });
  }
}

// Rate of BM_LeaseTableBatch by its args, the baseline of BM_GrpcBatch.
std::map<std::vector<int64_t>, double>& InProcessRates() {
  static std::map<std::vector<int64_t>, double> rates;
  return rates;
}

std::vector<int64_t> ArgsOf(const benchmark::State& state) {
  return {state.range(0), state.range(1), state.range(2)};
}

void BM_LeaseTableBatch(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  const int rounds = static_cast<int>(state.range(1));
  const int per = static_cast<int>(state.range(2));
  TempDir dir;
  auto store = JobStore::Open((dir.path() / "state.sqlite").string());
  if (!store.ok()) return state.SkipWithError("cannot open store");
  for (auto _ : state) {
    auto table = LeaseTable::Create(store->get(), nullptr, {.lease_ms = 60'000}, nullptr);
    const int64_t job = (*table)->ReserveJobId();
    PlannedJob plan{.tiles = workers * (rounds + 1) * per + 1,
                    .groups = 1,
                    .store_path = "bench" + std::to_string(job)};
    if (!(*table)->AddJob(job, "", 3, plan).ok()) return state.SkipWithError("AddJob failed");
    std::vector<int64_t> ids;
    for (int w = 0; w < workers; ++w) ids.push_back(*(*table)->RegisterWorker("bench", per));
    std::vector<std::vector<Completion>> held(workers);
    RunWorkers(state, workers, rounds, [&](int w, Latencies& lat) {
      const auto t0 = Clock::now();
      auto r = (*table)->Exchange(ids[w], held[w], per);
      lat.lease.push_back(Micros(Clock::now() - t0));
      held[w].clear();
      if (r.ok())
        for (const LeaseGrant& g : r->grants) held[w].push_back({g.key, {}});
    });
  }
  state.counters["lease_ops_per_s"] = state.counters["lease_ops_per_s"] * per;
  InProcessRates()[ArgsOf(state)] = state.counters["lease_ops_per_s"];
}

std::unique_ptr<grpc::ClientContext> Ctx() {
  auto ctx = std::make_unique<grpc::ClientContext>();
  ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  return ctx;
}

void BM_GrpcLoopback(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const int ops = static_cast<int>(state.range(1));
  TempDir dir;
  auto plan = [&](const v1::BakeRequest&) -> absl::StatusOr<PlannedJob> {
    return PlannedJob{.tiles = threads * ops + 1, .groups = 1};
  };
  CoordinatorOptions options{.data_dir = dir.path(), .lease_seconds = 60};
  auto coordinator = Coordinator::Start(options, plan, nullptr);
  if (!coordinator.ok()) return state.SkipWithError("cannot start coordinator");
  auto channel = grpc::CreateChannel((*coordinator)->address(), grpc::InsecureChannelCredentials());
  auto jobs = v1::JobService::NewStub(channel);
  auto stub = v1::WorkerService::NewStub(channel);
  for (auto _ : state) {
    v1::BakeRequest request;
    request.mutable_scene()->set_builtin("builtin:furnace");
    v1::Job job;
    if (!jobs->Submit(Ctx().get(), request, &job).ok()) return state.SkipWithError("Submit failed");
    std::vector<std::string> workers(threads);
    for (auto& id : workers) {
      v1::WorkerInfo info;
      info.set_threads(1);
      v1::WorkerId wid;
      (void)stub->Register(Ctx().get(), info, &wid);
      id = wid.id();
    }
    RunWorkers(state, threads, ops, [&](int t, Latencies& lat) {
      v1::LeaseRequest req;
      req.set_worker_id(workers[t]);
      v1::LeaseReply reply;
      const auto t0 = Clock::now();
      (void)stub->Lease(Ctx().get(), req, &reply);
      const auto t1 = Clock::now();
      v1::TaskResult result;
      result.set_worker_id(workers[t]);
      result.set_lease_id(reply.task().lease_id());
      v1::CompleteReply done;
      (void)stub->Complete(Ctx().get(), result, &done);
      lat.lease.push_back(Micros(t1 - t0));
      lat.complete.push_back(Micros(Clock::now() - t1));
    });
  }
  (*coordinator)->Shutdown();
}

// A coordinator with one job of `tasks` trivial tiles and `workers`
// registered workers of `per` threads, each with a connection of its own.
struct GrpcFarm {
  TempDir dir;
  std::unique_ptr<Coordinator> coordinator;
  std::vector<std::unique_ptr<v1::WorkerService::Stub>> stubs;
  std::vector<std::string> ids;

  absl::Status Start(int workers, int per, int tasks) {
    auto plan = [tasks](const v1::BakeRequest&) -> absl::StatusOr<PlannedJob> {
      return PlannedJob{.tiles = tasks, .groups = 1};
    };
    auto c = Coordinator::Start({.data_dir = dir.path(), .lease_seconds = 600}, plan, nullptr);
    if (!c.ok()) return c.status();
    coordinator = std::move(*c);
    for (int w = 0; w < workers; ++w) {
      grpc::ChannelArguments args;
      args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);  // a connection per worker
      auto channel = grpc::CreateCustomChannel(coordinator->address(),
                                               grpc::InsecureChannelCredentials(), args);
      stubs.push_back(v1::WorkerService::NewStub(channel));
    }
    v1::BakeRequest request;
    request.mutable_scene()->set_builtin("builtin:furnace");
    v1::Job job;
    auto jobs = v1::JobService::NewStub(
        grpc::CreateChannel(coordinator->address(), grpc::InsecureChannelCredentials()));
    if (!jobs->Submit(Ctx().get(), request, &job).ok()) return absl::InternalError("Submit");
    for (auto& stub : stubs) {
      v1::WorkerInfo info;
      info.set_threads(per);
      v1::WorkerId wid;
      if (!stub->Register(Ctx().get(), info, &wid).ok()) return absl::InternalError("Register");
      ids.push_back(wid.id());
    }
    return absl::OkStatus();
  }
};

void BM_GrpcBatch(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  const int rounds = static_cast<int>(state.range(1));
  const int per = static_cast<int>(state.range(2));
  for (auto _ : state) {
    GrpcFarm farm;
    if (!farm.Start(workers, per, workers * (rounds + 1) * per + 1).ok())
      return state.SkipWithError("cannot start the farm");
    std::vector<v1::LeaseBatchRequest> next(workers);
    int64_t errors = 0;
    RunWorkers(state, workers, rounds, [&](int w, Latencies& lat) {
      v1::LeaseBatchRequest& req = next[w];
      req.set_worker_id(farm.ids[w]);
      req.set_max_tasks(per);
      v1::LeaseBatchReply reply;
      const auto t0 = Clock::now();
      const grpc::Status s = farm.stubs[w]->LeaseBatch(Ctx().get(), req, &reply);
      lat.lease.push_back(Micros(Clock::now() - t0));
      req.clear_completed();
      if (!s.ok()) return (void)__atomic_add_fetch(&errors, 1, __ATOMIC_RELAXED);
      for (const v1::Task& t : reply.tasks()) req.add_completed()->set_lease_id(t.lease_id());
    });
    if (errors > 0) state.SkipWithError("LeaseBatch failed");
    farm.coordinator->Shutdown();
  }
  const double rate = state.counters["lease_ops_per_s"] * per;
  state.counters["lease_ops_per_s"] = rate;
  if (auto it = InProcessRates().find(ArgsOf(state)); it != InProcessRates().end())
    state.counters["vs_in_process"] = rate / it->second;
}

// Heartbeats of `workers` workers holding `per` leases each: calls/s.
void BM_GrpcHeartbeat(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  const int calls = static_cast<int>(state.range(1));
  const int per = static_cast<int>(state.range(2));
  for (auto _ : state) {
    GrpcFarm farm;
    if (!farm.Start(workers, per, workers * per + 1).ok())
      return state.SkipWithError("cannot start the farm");
    std::vector<v1::HeartbeatRequest> beats(workers);
    for (int w = 0; w < workers; ++w) {
      v1::LeaseBatchRequest req;
      req.set_worker_id(farm.ids[w]);
      req.set_max_tasks(per);
      v1::LeaseBatchReply reply;
      if (!farm.stubs[w]->LeaseBatch(Ctx().get(), req, &reply).ok())
        return state.SkipWithError("LeaseBatch failed");
      beats[w].set_worker_id(farm.ids[w]);
      for (const v1::Task& t : reply.tasks()) beats[w].add_leases()->set_lease_id(t.lease_id());
    }
    RunWorkers(state, workers, calls, [&](int w, Latencies& lat) {
      v1::HeartbeatReply reply;
      const auto t0 = Clock::now();
      (void)farm.stubs[w]->Heartbeat(Ctx().get(), beats[w], &reply);
      lat.lease.push_back(Micros(Clock::now() - t0));
    });
    farm.coordinator->Shutdown();
  }
  state.counters["heartbeats_per_s"] = state.counters["lease_ops_per_s"];
  state.counters.erase("lease_ops_per_s");
}

// Args: {worker threads, lease ops per thread}.
BENCHMARK(BM_SqliteTxn)
    ->Args({1, 20000})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JobStoreCommit)
    ->Args({1, 20000})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LeaseTableMemory)
    ->Args({1, 50000})
    ->Args({8, 10000})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LeaseTableSqlite)
    ->Args({1, 10000})
    ->Args({8, 2500})
    ->Args({32, 500})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GrpcLoopback)
    ->Args({1, 1000})
    ->Args({8, 500})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
// Args: {simulated workers, rounds per worker, threads per worker}.
BENCHMARK(BM_LeaseTableBatch)
    ->Args({256, 40, 1})
    ->Args({256, 40, 4})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GrpcBatch)
    ->Args({256, 40, 1})
    ->Args({256, 40, 4})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GrpcHeartbeat)
    ->Args({256, 40, 4})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
