// The job client (driver/jobs/job_submit.h, job_watch.h, job_query.h,
// store_fetch.h) against a real coordinator on a TCP port with one worker
// loop: a scene file is uploaded once by content hash, a watch sees every
// persisted event once and in order, status and cancel report the job, and
// fetch writes a store identical to the one on the coordinator's disk — or
// nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "coordinator/service/coordinator.h"
#include "coordinator/service/job_planner.h"
#include "driver/jobs/client.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_submit.h"
#include "driver/jobs/job_watch.h"
#include "driver/jobs/store_fetch.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"
#include "worker/loop/worker_loop.h"

namespace wavebake::driver {
namespace {

using test_support::ReadTree;
using test_support::ScratchDir;

v1::BakeRequest SmallRequest(const std::string& output_name,
                             const std::string& layout = "camera:16x16") {
  v1::BakeRequest r;
  r.set_light_res(8);
  r.set_supersample(1);
  r.set_layout(layout);
  r.set_tile_size(4);
  r.set_output_name(output_name);
  return r;
}

class JobClientTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::filesystem::path data = dir_.path() / "data";
    store_root_ = data / "store";
    absl::StatusOr<std::unique_ptr<Coordinator>> c = Coordinator::Start(
        {.listen_address = "127.0.0.1:0",
         .data_dir = data,
         .store_root = store_root_,
         .wait_ms = 10},
        MakeJobPlanner({.data_dir = data, .store_root = store_root_, .local_scenes = {}}),
        MakeJobCleanup(store_root_));
    ASSERT_TRUE(c.ok()) << c.status();
    coordinator_ = std::move(*c);
    absl::StatusOr<Client> client = Client::Connect({.coordinator = coordinator_->address()});
    ASSERT_TRUE(client.ok()) << client.status();
    client_ = std::make_unique<Client>(*std::move(client));
  }
  void StartWorker() {
    worker_ = std::make_unique<WorkerLoop>(client_->channel(),
                                           WorkerOptions{.store_root = store_root_, .threads = 1});
    worker_thread_ = std::thread([this] { (void)worker_->Run(); });
  }
  void TearDown() override {
    if (worker_) worker_->Drain();
    if (worker_thread_.joinable()) worker_thread_.join();
    if (coordinator_) coordinator_->Shutdown();
  }

  ScratchDir dir_;
  std::filesystem::path store_root_;
  std::unique_ptr<Coordinator> coordinator_;
  std::unique_ptr<Client> client_;
  std::unique_ptr<WorkerLoop> worker_;
  std::thread worker_thread_;
};

TEST_F(JobClientTest, SubmitWatchStatusAndFetch) {
  const auto mesh = dir_.path() / "tent.obj";
  std::ofstream(mesh)
      << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0.6 0\nf 1 3 2\nf 1 4 3\nf 1 2 5\nf 2 3 5\n";
  StartWorker();
  absl::StatusOr<v1::Job> job =
      SubmitScene(*client_, SmallRequest("a.wbk", "hilbert:4x4"), mesh.string());
  ASSERT_TRUE(job.ok()) << job.status();
  std::vector<v1::JobEvent> events;
  absl::StatusOr<v1::Job> ended = WatchJob(
      *client_, job->id(), {.on_event = [&](const v1::JobEvent& e) { events.push_back(e); }});
  ASSERT_TRUE(ended.ok()) << ended.status();
  ASSERT_EQ(ended->phase(), v1::PHASE_DONE) << ended->error();
  int64_t seq = 0;
  for (const v1::JobEvent& e : events) {
    if (e.kind() == v1::EVENT_PROGRESS) continue;
    EXPECT_GT(e.seq(), seq) << "a persisted event delivered twice or out of order";
    seq = e.seq();
  }
  EXPECT_EQ(events.back().phase(), v1::PHASE_DONE);

  // The same file again: the coordinator has it, so only the job is sent.
  absl::StatusOr<v1::Job> again =
      SubmitScene(*client_, SmallRequest("b.wbk", "hilbert:4x4"), mesh.string());
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(again->request().scene().uploaded().sha256(),
            job->request().scene().uploaded().sha256());

  absl::StatusOr<v1::Job> status = GetJob(*client_, job->id());
  ASSERT_TRUE(status.ok()) << status.status();
  EXPECT_EQ(status->tasks_done(), status->tasks_total());
  // Watching a job that has ended replays its events at its own rate (its
  // rays over its baking time), not its rays over the watch's milliseconds.
  ASSERT_GT(status->rays_per_second(), 0);
  std::vector<v1::JobEvent> replayed;
  ASSERT_TRUE(WatchJob(*client_, job->id(), {.on_event = [&](const v1::JobEvent& e) {
                replayed.push_back(e);
              }}).ok());
  ASSERT_FALSE(replayed.empty());
  for (const v1::JobEvent& e : replayed)
    EXPECT_DOUBLE_EQ(e.rays_per_second(), status->rays_per_second()) << e.seq();
  absl::StatusOr<std::vector<v1::Job>> jobs = ListJobs(*client_, 10, /*active_only=*/false);
  ASSERT_TRUE(jobs.ok()) << jobs.status();
  EXPECT_EQ(jobs->size(), 2u);
  EXPECT_EQ(GetJob(*client_, "999").status().code(), absl::StatusCode::kNotFound);
  // A job that ended otherwise cannot be cancelled.
  EXPECT_EQ(CancelJob(*client_, job->id()).status().code(), absl::StatusCode::kFailedPrecondition);

  const auto fetched = dir_.path() / "fetched.wbk";
  absl::StatusOr<FetchSummary> summary = FetchStore(*client_, job->id(), fetched);
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_GT(summary->arrays, 5);
  EXPECT_TRUE(ReadTree(fetched) == ReadTree(store_root_ / "a.wbk"));
  // An existing destination is never overwritten.
  EXPECT_EQ(FetchStore(*client_, job->id(), fetched).status().code(),
            absl::StatusCode::kAlreadyExists);
}

TEST_F(JobClientTest, CancelAQueuedJob) {
  v1::BakeRequest r = SmallRequest("c.wbk");
  absl::StatusOr<v1::Job> job = SubmitScene(*client_, r, "builtin:furnace");  // no worker yet
  ASSERT_TRUE(job.ok()) << job.status();
  absl::StatusOr<v1::Job> cancelled = CancelJob(*client_, job->id());
  ASSERT_TRUE(cancelled.ok()) << cancelled.status();
  EXPECT_EQ(cancelled->phase(), v1::PHASE_CANCELLED);
  EXPECT_THAT(JobOutcome(*cancelled), ::testing::HasSubstr("CANCELLED"));
  // Cancelling again is no error: the job stays CANCELLED.
  absl::StatusOr<v1::Job> again = CancelJob(*client_, job->id());
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(again->phase(), v1::PHASE_CANCELLED);
  absl::StatusOr<v1::Job> watched = WatchJob(*client_, job->id());
  ASSERT_TRUE(watched.ok()) << watched.status();
  EXPECT_EQ(watched->phase(), v1::PHASE_CANCELLED);
}

// Named as the setting (Client::Config's field), the same words for the
// command line and Python.
TEST_F(JobClientTest, ABadConfigurationNamesItsSetting) {
  EXPECT_THAT(Client::Connect({.coordinator = "127.0.0.1:1", .token_file = "/no/such/token"})
                  .status()
                  .message(),
              ::testing::HasSubstr("token_file: "));
  EXPECT_THAT(std::string(Client::Connect({.coordinator = "127.0.0.1:1"}, /*connect_seconds=*/0.2)
                              .status()
                              .message()),
              ::testing::StartsWith("coordinator: cannot connect"));
}

}  // namespace
}  // namespace wavebake::driver
