#include "driver/bake/embedded_bake.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "coordinator/service/coordinator.h"
#include "coordinator/service/job_planner.h"
#include "driver/bake/update_bake.h"
#include "driver/jobs/client.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_submit.h"
#include "driver/jobs/job_watch.h"
#include "proto/bake_request.h"
#include "storage/files/scoped_dir.h"
#include "worker/columns/publish_store.h"
#include "worker/loop/worker_loop.h"

namespace wavebake::driver {
namespace {

// The store's name inside the temporary store root (any valid output_name).
constexpr char kStoreName[] = "bake.wbk";

// The worker loops, each on its own thread, drained and joined on destruction.
class Workers {
 public:
  Workers(const Coordinator& coordinator, std::shared_ptr<grpc::Channel> channel, int count,
          const std::map<std::string, std::string>& local_scenes, uint64_t memory_staging_bytes) {
    const std::filesystem::path store_root = coordinator.options().store_root;
    // One context and scene cache for the process: a job's BakeContext (scene,
    // samples, Embree scene) is built once, whatever the number of loops.
    auto contexts = std::make_shared<ContextCache>(2);
    auto scenes = std::make_shared<SceneCache>(store_root / ".scene-cache", local_scenes);
    // Every task runs in one of these loops: staging may stay in memory.
    auto memory =
        memory_staging_bytes > 0 ? std::make_shared<MemoryStaging>(memory_staging_bytes) : nullptr;
    for (int i = 0; i < count; ++i) {
      WorkerOptions options;
      options.store_root = store_root;
      options.threads = 1;
      options.name = absl::StrCat("bake-", i);
      options.contexts = contexts;
      options.scenes = scenes;
      options.memory_staging = memory;
      loops_.push_back(std::make_unique<WorkerLoop>(channel, std::move(options)));
    }
    for (auto& loop : loops_) {
      threads_.emplace_back([this, loop = loop.get()] {
        absl::Status s = loop->Run();
        std::lock_guard lock(mu_);
        if (!s.ok() && error_.ok()) error_ = s;
        ++stopped_;
      });
    }
  }
  ~Workers() {
    for (auto& loop : loops_) loop->Drain();
    for (std::thread& t : threads_) t.join();
  }
  // Stops the running tasks too (a job that ended otherwise than DONE, or a
  // watch that failed): nothing they would still write is wanted, and a task
  // does not wait for a heartbeat to learn it.
  void Abort() {
    for (auto& loop : loops_) loop->Abort();
  }

  // Every loop has ended before being drained: no task will run any more.
  bool AllStopped() const {
    std::lock_guard lock(mu_);
    return stopped_ == static_cast<int>(loops_.size());
  }
  absl::Status error() const {
    std::lock_guard lock(mu_);
    return error_;
  }

 private:
  std::vector<std::unique_ptr<WorkerLoop>> loops_;
  std::vector<std::thread> threads_;
  mutable std::mutex mu_;
  int stopped_ = 0;
  absl::Status error_;
};

// Cancels the job once `interrupted` rises or no worker is left to run it
// (the watch meanwhile blocks in its stream).
class Watchdog {
 public:
  Watchdog(const Client& client, std::string job_id, const std::atomic<bool>* interrupted,
           const Workers& workers)
      : thread_([&client, job_id = std::move(job_id), interrupted, &workers](std::stop_token stop) {
          while (!stop.stop_requested()) {
            if ((interrupted && interrupted->load()) || workers.AllStopped()) {
              (void)CancelJob(client, job_id);
              return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          }
        }) {}

 private:
  std::jthread thread_;
};

// When the job entered and left BAKE_TILE, from its events.
class PhaseClock {
 public:
  explicit PhaseClock(std::chrono::steady_clock::time_point start)
      : baking_(start), after_(start) {}
  void Saw(v1::Phase phase) {
    const auto now = std::chrono::steady_clock::now();
    if (phase == v1::PHASE_BAKING && !in_baking_) {
      in_baking_ = true;
      baking_ = now;
    }
    if (phase > v1::PHASE_BAKING && !after_seen_) {
      after_seen_ = true;
      after_ = now;
    }
  }
  double BakingSeconds() const {
    return after_seen_ ? std::chrono::duration<double>(after_ - baking_).count() : 0.0;
  }

 private:
  std::chrono::steady_clock::time_point baking_, after_;
  bool in_baking_ = false, after_seen_ = false;
};

// Calls on_ending once, on whichever way EmbeddedBake leaves after
// on_started, while the coordinator still runs.
class EndingCall {
 public:
  EndingCall(const EmbeddedBakeOptions& options, Coordinator& coordinator)
      : options_(options), coordinator_(coordinator) {}
  ~EndingCall() { Call(); }
  void Call() {
    if (called_ || !options_.on_ending) return;
    called_ = true;
    options_.on_ending(coordinator_, job_id);
  }
  std::string job_id;  // empty until the job is submitted

 private:
  const EmbeddedBakeOptions& options_;
  Coordinator& coordinator_;
  bool called_ = false;
};

}  // namespace

absl::StatusOr<v1::Job> EmbeddedBake(const std::string& scene, const BakeParams& given,
                                     const std::filesystem::path& out,
                                     const EmbeddedBakeOptions& options) {
  if (absl::Status s = CheckOutputPath(out); !s.ok()) return s;
  BakeParams params = given;
  if (absl::Status s = PrepareUpdate(params); !s.ok()) return s;  // before anything is written
  if (!params.update_from.empty()) {
    absl::StatusOr<bool> copied = CopyIfUnchanged(scene, params, out);
    if (!copied.ok()) return copied.status();
    if (*copied) {  // nothing to rebake (no job ran)
      v1::Job done;
      done.set_phase(v1::PHASE_DONE);
      return done;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  PhaseClock phases(start);
  std::map<std::string, std::string> local_scenes;  // sha256 -> the path as given
  if (!IsBuiltinScene(scene)) {
    absl::StatusOr<SceneFile> file = ReadSceneFile(scene);
    if (!file.ok()) return file.status();
    local_scenes[file->sha256] = scene;
  }
  // The coordinator's data directory, beside the output so the store moves
  // to it by rename.
  absl::StatusOr<ScopedDir> data = ScopedDir::CreateBeside(out, "bake");
  if (!data.ok()) return data.status();
  const std::filesystem::path store_root = data->path() / "store";
  const PlannerOptions planner{.data_dir = data->path(),
                               .store_root = store_root,
                               .local_scenes = local_scenes,
                               .local_updates = true};
  absl::StatusOr<std::unique_ptr<Coordinator>> coordinator = Coordinator::Start(
      {.listen_address = "",  // in-process only
       .data_dir = data->path(),
       .store_root = store_root,
       // One process: excluding one of its loops for failing tasks helps
       // nobody; max_attempts still fails a job that fails everywhere.
       .worker_failure_limit = 1 << 30,
       .wait_ms = 10,         // idle workers ask again soon: a phase's last task is not a wait
       .hide_paths = false},  // the client is this machine's user
      MakeJobPlanner(planner), MakeJobCleanup(store_root));
  if (!coordinator.ok()) return coordinator.status();
  if (options.on_started) options.on_started(**coordinator, planner);
  EndingCall ending(options, **coordinator);
  const Client client((*coordinator)->InProcessChannel(), "");

  const int workers = options.workers > 0
                          ? options.workers
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  absl::StatusOr<v1::Job> job;
  {
    Workers loops(**coordinator, (*coordinator)->InProcessChannel(), workers, local_scenes,
                  options.memory_staging_bytes);
    v1::BakeRequest request = ToBakeRequest(params);
    request.set_output_name(kStoreName);
    absl::StatusOr<v1::Job> submitted = SubmitScene(client, request, scene, /*with_files=*/false);
    if (!submitted.ok()) return submitted.status();
    ending.job_id = submitted->id();
    Watchdog watchdog(client, submitted->id(), options.interrupted, loops);
    job = WatchJob(client, submitted->id(),
                   {.patience_seconds = 60, .on_event = [&](const v1::JobEvent& e) {
                      phases.Saw(e.phase());
                      if (options.on_event) options.on_event(e);
                    }});
    if (job.ok() && job->phase() == v1::PHASE_CANCELLED && loops.AllStopped() &&
        !loops.error().ok()) {
      job = loops.error();  // the workers' own failure, not a user's cancel
    }
    if (!job.ok() || job->phase() != v1::PHASE_DONE) loops.Abort();
  }  // workers drained: nothing writes any more
  ending.Call();
  if (job.ok() && job->phase() == v1::PHASE_DONE) {
    if (!params.update_from.empty()) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (absl::Status s =
              RecordUpdateTimes(store_root / job->store_path(), seconds, phases.BakingSeconds());
          !s.ok())
        return s;
    }
    if (absl::Status s = PublishStore(store_root / job->store_path(), out); !s.ok()) return s;
  }
  (*coordinator)->Shutdown();
  return job;
}

}  // namespace wavebake::driver
