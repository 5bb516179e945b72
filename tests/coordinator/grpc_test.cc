// The coordinator over gRPC on 127.0.0.1 (and in-process): a job end to end
// with fake workers, auth, INVALID_ARGUMENT / NOT_FOUND, uploads (§4).
#include <gmock/gmock.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <future>
#include <map>
#include <thread>

#include "absl/strings/str_cat.h"
#include "coordinator/service/coordinator.h"
#include "coordinator/state/scene_store.h"
#include "tests/coordinator/fake_worker.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using testing::CallContext;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr int kTiles = 6, kGroups = 3;

// Stands in for the real planner: a fixed shape; "builtin:empty" is a scene
// the planner rejects the way a mesh loader would.
absl::StatusOr<PlannedJob> FakePlan(const v1::BakeRequest& r) {
  if (r.scene().builtin() == "builtin:empty") {
    return absl::InvalidArgumentError("scene: the mesh has no vertices");
  }
  return PlannedJob{.tiles = kTiles, .groups = kGroups, .total_rays_estimate = kTiles * 1000};
}

class GrpcTest : public ::testing::Test {
 protected:
  void Start(std::string token = "", int64_t max_upload = 1 << 20, double lease_seconds = 5) {
    token_ = token;
    CoordinatorOptions o{.listen_address = "127.0.0.1:0",
                         .data_dir = dir_.path(),
                         .token = token,
                         .lease_seconds = lease_seconds,
                         .max_upload_bytes = max_upload,
                         .wait_ms = 20};
    auto c = Coordinator::Start(o, FakePlan, nullptr);
    ASSERT_TRUE(c.ok()) << c.status();
    coordinator_ = std::move(*c);
    ASSERT_GT(coordinator_->port(), 0);
    channel_ = grpc::CreateChannel(coordinator_->address(), grpc::InsecureChannelCredentials());
    jobs_ = v1::JobService::NewStub(channel_);
    workers_ = v1::WorkerService::NewStub(channel_);
  }

  grpc::Status Submit(const v1::BakeRequest& r, v1::Job* job = nullptr) {
    v1::Job ignored;
    return jobs_->Submit(CallContext(token_).get(), r, job ? job : &ignored);
  }

  absl::StatusOr<v1::SceneRef> Upload(const std::string& bytes, const std::string& name,
                                      size_t chunk) {
    auto ctx = CallContext(token_);
    v1::SceneRef ref;
    auto writer = jobs_->UploadScene(ctx.get(), &ref);
    for (size_t off = 0; off < bytes.size(); off += chunk) {
      v1::SceneChunk c;
      if (off == 0) c.set_file_name(name);
      c.set_data(bytes.substr(off, chunk));
      if (!writer->Write(c)) break;
    }
    writer->WritesDone();
    grpc::Status s = writer->Finish();
    if (!s.ok())
      return absl::Status(static_cast<absl::StatusCode>(s.error_code()), s.error_message());
    return ref;
  }

  // Registers a worker and leases one task by hand.
  v1::Task LeaseOne(std::string* worker_id) {
    v1::WorkerInfo info;
    info.set_threads(1);
    v1::WorkerId wid;
    EXPECT_TRUE(workers_->Register(CallContext(token_).get(), info, &wid).ok());
    *worker_id = wid.id();
    v1::LeaseRequest lease;
    lease.set_worker_id(wid.id());
    v1::LeaseReply reply;
    EXPECT_TRUE(workers_->Lease(CallContext(token_).get(), lease, &reply).ok());
    EXPECT_TRUE(reply.has_task());
    return reply.task();
  }

  int SceneFiles() const {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir_.path() / "scenes"))
      n += e.is_regular_file();
    return n;
  }

  testing::TempDir dir_;
  std::string token_;
  std::unique_ptr<Coordinator> coordinator_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::JobService::Stub> jobs_;
  std::unique_ptr<v1::WorkerService::Stub> workers_;
};

TEST_F(GrpcTest, FakeWorkersCompleteAJobAndWatchSeesEveryPhase) {
  Start("tok");
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  EXPECT_EQ(job.phase(), v1::PHASE_QUEUED);
  EXPECT_EQ(job.tasks_total(), kTiles + kGroups + FinalizeShards(kGroups) + 1);
  EXPECT_EQ(job.request().light_res(), 32);  // defaults filled in
  EXPECT_EQ(job.request().column_mode(), "adaptive");
  EXPECT_EQ(job.store_path(), "job-" + job.id() + ".wbk");

  const std::filesystem::path store_root = dir_.path() / "store";
  std::vector<std::unique_ptr<testing::FakeWorker>> workers;
  workers.push_back(std::make_unique<testing::FakeWorker>(channel_, "tok", store_root));
  workers.push_back(std::make_unique<testing::FakeWorker>(channel_, "tok", store_root));
  workers.push_back(  // the embedded mode's path: same services, no socket
      std::make_unique<testing::FakeWorker>(coordinator_->InProcessChannel(), "tok", store_root));
  for (auto& w : workers) w->Start();

  v1::JobId id;
  id.set_id(job.id());
  auto ctx = CallContext("tok", 20'000);
  auto stream = jobs_->Watch(ctx.get(), id);
  std::vector<v1::Phase> phases;
  std::map<v1::EventKind, int> kinds;
  v1::JobEvent event, last;
  int64_t last_seq = 0;
  while (stream->Read(&event)) {
    ++kinds[event.kind()];
    if (event.kind() == v1::EVENT_PHASE || event.kind() == v1::EVENT_SUBMITTED) {
      phases.push_back(event.phase());
    }
    if (event.kind() != v1::EVENT_PROGRESS) {
      EXPECT_GT(event.seq(), last_seq);
      last_seq = event.seq();
    }
    last = event;
  }
  ASSERT_TRUE(stream->Finish().ok());
  for (auto& w : workers) w->Stop();

  EXPECT_THAT(phases, ElementsAre(v1::PHASE_QUEUED, v1::PHASE_BAKING, v1::PHASE_TRANSFORMING,
                                  v1::PHASE_FINALIZING, v1::PHASE_DONE));
  EXPECT_EQ(kinds[v1::EVENT_TASK_DONE], kTiles + kGroups + FinalizeShards(kGroups) + 1);
  EXPECT_EQ(kinds[v1::EVENT_TASK_LEASED], kTiles + kGroups + FinalizeShards(kGroups) + 1);
  EXPECT_EQ(last.phase(), v1::PHASE_DONE);
  EXPECT_EQ(last.tasks_done(), kTiles + kGroups + FinalizeShards(kGroups) + 1);
  EXPECT_EQ(last.stats_json(), R"({"rel_rms": 0.01})");
  int completed = 0;
  for (auto& w : workers) completed += w->completed();
  EXPECT_EQ(completed, kTiles + kGroups + FinalizeShards(kGroups) + 1);

  v1::Job done;
  ASSERT_TRUE(jobs_->Get(CallContext("tok").get(), id, &done).ok());
  EXPECT_EQ(done.phase(), v1::PHASE_DONE);
  EXPECT_EQ(done.rays_traced(), kTiles * 1000);
  EXPECT_EQ(done.bytes_written(), 10 * (kTiles + kGroups + FinalizeShards(kGroups) + 1));

  // ReadStore streams every file of the finished store.
  auto read_ctx = CallContext("tok");
  auto files = jobs_->ReadStore(read_ctx.get(), id);
  std::map<std::string, std::string> got;
  v1::FileChunk chunk;
  while (files->Read(&chunk)) {
    EXPECT_EQ(chunk.offset(), static_cast<int64_t>(got[chunk.path()].size()));
    got[chunk.path()] += chunk.data();
  }
  ASSERT_TRUE(files->Finish().ok());
  EXPECT_EQ(got.size(), 2u);
  EXPECT_EQ(got[".zgroup"], R"({"zarr_format": 2})");
  EXPECT_EQ(got["transport/data"], std::string(3000, 'x'));
}

TEST_F(GrpcTest, MissingOrWrongTokenIsUnauthenticated) {
  Start("s3cret");
  v1::JobId id;
  id.set_id("1");
  v1::Job job;
  EXPECT_EQ(jobs_->Get(CallContext("").get(), id, &job).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(jobs_->Get(CallContext("wrong").get(), id, &job).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(jobs_->Get(CallContext("s3cret").get(), id, &job).error_code(),
            grpc::StatusCode::NOT_FOUND);
  v1::WorkerInfo info;
  info.set_threads(1);
  v1::WorkerId wid;
  EXPECT_EQ(workers_->Register(CallContext("").get(), info, &wid).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  auto ctx = CallContext("");
  auto stream = jobs_->Watch(ctx.get(), id);
  v1::JobEvent e;
  EXPECT_FALSE(stream->Read(&e));
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

// grpc.health.v1.Health/Check of `service` on a channel, by hand (the
// project generates no health stubs): the response's bytes, or the error.
absl::StatusOr<std::string> HealthCheck(const std::shared_ptr<grpc::Channel>& channel,
                                        const std::string& service) {
  grpc::GenericStub stub(channel);
  // HealthCheckRequest{service: 1}, a length-delimited field.
  const std::string body =
      service.empty()
          ? std::string{}
          : absl::StrCat("\x0a", std::string(1, static_cast<char>(service.size())), service);
  grpc::Slice slice(body);
  grpc::ByteBuffer request(&slice, 1), response;
  std::promise<grpc::Status> done;
  auto ctx = CallContext("");
  stub.UnaryCall(ctx.get(), "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request,
                 &response, [&](grpc::Status s) { done.set_value(s); });
  const grpc::Status s = done.get_future().get();
  if (!s.ok())
    return absl::Status(static_cast<absl::StatusCode>(s.error_code()), s.error_message());
  std::vector<grpc::Slice> slices;
  if (!response.Dump(&slices).ok()) return absl::DataLossError("response");
  std::string bytes;
  for (const auto& sl : slices) bytes.append(reinterpret_cast<const char*>(sl.begin()), sl.size());
  return bytes;
}

// grpc.health.v1.Health/Check of the whole server, without a token: the
// HealthCheckResponse's bytes ("" when the call failed).
std::string HealthBytes(const std::shared_ptr<grpc::Channel>& channel) {
  return HealthCheck(channel, "").value_or("");
}
const std::string kServing("\x08\x01", 2), kNotServing("\x08\x02", 2);  // status: 1, 2

TEST_F(GrpcTest, HealthCheckServesWithoutToken) {
  Start("s3cret");
  EXPECT_EQ(HealthBytes(channel_), kServing);
}

// A database that cannot record a change (every commit refused, as on a full
// disk): the failed submit stops the table, the reaper's recoveries fail too
// (each would record the unfinished job's resumption), and health says
// NOT_SERVING instead of a SERVING whose every call fails; once commits work
// again the reaper recovers the table and health is SERVING, no restart.
TEST_F(GrpcTest, HealthIsNotServingWhileTheStateCannotBeRecorded) {
  Start("", 1 << 20, /*lease_seconds=*/0.2);            // the reaper ticks every 50 ms
  ASSERT_TRUE(Submit(testing::BuiltinRequest()).ok());  // unfinished: recovery must commit
  coordinator_->job_store().SetFullForTesting(true);
  EXPECT_EQ(Submit(testing::BuiltinRequest()).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  // Polled, each wait bounded: the reaper sets it at its next tick.
  auto health_becomes = [&](const std::string& want) {
    for (int i = 0; i < 100; ++i) {
      if (HealthBytes(channel_) == want) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  };
  EXPECT_TRUE(health_becomes(kNotServing));
  EXPECT_FALSE(coordinator_->table().broken().ok());
  coordinator_->job_store().SetFullForTesting(false);
  EXPECT_TRUE(health_becomes(kServing));
  EXPECT_TRUE(Submit(testing::BuiltinRequest()).ok());
}

TEST_F(GrpcTest, BadRequestsNameTheField) {
  Start();
  struct Case {
    std::function<void(v1::BakeRequest&)> edit;
    std::string field;
  };
  const std::vector<Case> cases = {
      {[](auto& r) { r.set_light_res(33); }, "light_res: 33 is not a power of two in 8..256"},
      {[](auto& r) { r.set_target_error(-0.5); }, "target_error:"},
      {[](auto& r) { r.set_target_error(std::nan("")); }, "target_error:"},
      {[](auto& r) { r.set_column_mode("4d"); }, "column_mode:"},
      {[](auto& r) { r.set_column_filter("db2"); }, "column_filter:"},
      {[](auto& r) { r.set_layout("spiral"); }, "layout:"},
      {[](auto& r) { r.set_layout("hilbert:100x64"); }, "layout:"},
      {[](auto& r) { r.set_bits(17); }, "bits:"},
      {[](auto& r) { r.set_supersample(-1); }, "supersample:"},
      {[](auto& r) { r.set_max_attempts(-2); }, "max_attempts:"},
      {[](auto& r) { r.set_output_name("../etc"); }, "output_name:"},
      {[](auto& r) { r.clear_scene(); }, "scene:"},
      {[](auto& r) { r.mutable_scene()->set_builtin("builtin:Bad Name"); }, "scene.builtin:"},
      {[](auto& r) { r.mutable_scene()->mutable_uploaded()->set_sha256(std::string(64, 'f')); },
       "scene.uploaded.sha256: no uploaded scene"},
      {[](auto& r) { r.mutable_scene()->set_builtin("builtin:empty"); },
       "scene: the mesh has no vertices"},
  };
  for (const Case& c : cases) {
    v1::BakeRequest r = testing::BuiltinRequest();
    c.edit(r);
    grpc::Status s = Submit(r);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.field;
    EXPECT_THAT(s.error_message(), HasSubstr(c.field));
  }
  v1::LeaseRequest lease;
  lease.set_worker_id("not-a-number");
  v1::LeaseReply reply;
  grpc::Status s = workers_->Lease(CallContext("").get(), lease, &reply);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(s.error_message(), HasSubstr("worker_id:"));
  v1::HeartbeatRequest hb;
  hb.set_worker_id("1");
  hb.add_leases()->set_lease_id("garbage");
  v1::HeartbeatReply hb_reply;
  s = workers_->Heartbeat(CallContext("").get(), hb, &hb_reply);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(s.error_message(), HasSubstr("leases[0].lease_id:"));
  // Nothing half-made: no job was created by any of these.
  v1::JobList list;
  ASSERT_TRUE(jobs_->List(CallContext("").get(), v1::ListRequest(), &list).ok());
  EXPECT_EQ(list.jobs_size(), 0);
}

TEST_F(GrpcTest, UnknownJobOrWorkerIsNotFound) {
  Start();
  v1::JobId id;
  id.set_id("999");
  v1::Job job;
  EXPECT_EQ(jobs_->Get(CallContext("").get(), id, &job).error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(jobs_->Cancel(CallContext("").get(), id, &job).error_code(),
            grpc::StatusCode::NOT_FOUND);
  auto ctx = CallContext("");
  auto stream = jobs_->Watch(ctx.get(), id);
  v1::JobEvent e;
  while (stream->Read(&e)) {
  }
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::NOT_FOUND);
  v1::LeaseRequest lease;
  lease.set_worker_id("999");
  v1::LeaseReply reply;
  EXPECT_EQ(workers_->Lease(CallContext("").get(), lease, &reply).error_code(),
            grpc::StatusCode::NOT_FOUND);
  id.set_id("abc");
  EXPECT_EQ(jobs_->Get(CallContext("").get(), id, &job).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
}

TEST_F(GrpcTest, SameSceneUploadedTwiceIsStoredOnce) {
  Start();
  std::string bytes;
  for (int i = 0; i < 5000; ++i) bytes += "v " + std::to_string(i) + " 0 1\n";
  auto a = Upload(bytes, "/home/me/bunny.obj", 4096);
  auto b = Upload(bytes, "copy.obj", 1000);  // other name, other chunking
  ASSERT_TRUE(a.ok()) << a.status();
  ASSERT_TRUE(b.ok()) << b.status();
  EXPECT_EQ(a->sha256(), Sha256Hex(bytes));
  EXPECT_EQ(a->sha256(), b->sha256());
  EXPECT_EQ(a->size(), static_cast<int64_t>(bytes.size()));
  EXPECT_EQ(a->file_name(), "bunny.obj");  // directories are dropped
  EXPECT_EQ(SceneFiles(), 1);

  // Workers fetch it back by hash.
  v1::SceneRef ref;
  ref.set_sha256(a->sha256());
  auto ctx = CallContext("");
  auto stream = workers_->FetchScene(ctx.get(), ref);
  std::string fetched;
  v1::SceneChunk chunk;
  while (stream->Read(&chunk)) fetched += chunk.data();
  ASSERT_TRUE(stream->Finish().ok());
  EXPECT_EQ(fetched, bytes);

  // And a job can name it.
  v1::BakeRequest r;
  *r.mutable_scene()->mutable_uploaded() = *a;
  v1::Job job;
  ASSERT_TRUE(Submit(r, &job).ok());
  EXPECT_EQ(job.request().scene().uploaded().sha256(), a->sha256());
}

// Oversized uploads are INVALID_ARGUMENT (DESIGN.md §4 lists "oversized
// upload" among the bad inputs), naming the `data` field; nothing is kept.
TEST_F(GrpcTest, OversizedUploadIsInvalidArgumentAndLeavesNothing) {
  Start("", /*max_upload=*/10'000);
  auto r = Upload(std::string(25'000, 'x'), "big.ply", 4096);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(r.status().message(), HasSubstr("data: upload exceeds"));
  EXPECT_EQ(SceneFiles(), 0);
  auto ok = Upload(std::string(10'000, 'x'), "fits.ply", 4096);
  EXPECT_TRUE(ok.ok()) << ok.status();
  EXPECT_FALSE(Upload("", "empty.obj", 10).ok());
}

TEST_F(GrpcTest, CancelAnswersHeartbeatAndRemovesPartialStore) {
  Start();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  v1::WorkerInfo info;
  info.set_threads(1);
  v1::WorkerId wid;
  ASSERT_TRUE(workers_->Register(CallContext("").get(), info, &wid).ok());
  v1::LeaseRequest lease;
  lease.set_worker_id(wid.id());
  v1::LeaseReply reply;
  ASSERT_TRUE(workers_->Lease(CallContext("").get(), lease, &reply).ok());
  ASSERT_TRUE(reply.has_task());
  const std::filesystem::path partial = dir_.path() / "store" / reply.task().store_path();
  std::filesystem::create_directories(partial / "staging");

  v1::JobId id;
  id.set_id(job.id());
  v1::Job cancelled;
  ASSERT_TRUE(jobs_->Cancel(CallContext("").get(), id, &cancelled).ok());
  EXPECT_EQ(cancelled.phase(), v1::PHASE_CANCELLED);
  EXPECT_TRUE(std::filesystem::exists(partial));  // the worker still holds a lease

  v1::HeartbeatRequest hb;
  hb.set_worker_id(wid.id());
  hb.add_leases()->set_lease_id(reply.task().lease_id());
  v1::HeartbeatReply hb_reply;
  ASSERT_TRUE(workers_->Heartbeat(CallContext("").get(), hb, &hb_reply).ok());
  EXPECT_THAT(hb_reply.cancelled_lease_ids(), ElementsAre(reply.task().lease_id()));
  EXPECT_FALSE(std::filesystem::exists(partial));  // default cleanup removed it
  // ReadStore only serves DONE jobs.
  auto ctx = CallContext("");
  auto files = jobs_->ReadStore(ctx.get(), id);
  v1::FileChunk chunk;
  EXPECT_FALSE(files->Read(&chunk));
  EXPECT_EQ(files->Finish().error_code(), grpc::StatusCode::FAILED_PRECONDITION);
}

// A worker whose --store-root is spelled unlike the coordinator's (another
// mount): its failure reason reaches clients without the worker's path.
TEST_F(GrpcTest, JobErrorCarriesNoPathOfTheWorker) {
  Start();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  std::string worker_id;
  const v1::Task task = LeaseOne(&worker_id);
  v1::TaskFailure failure;
  failure.set_worker_id(worker_id);
  failure.set_lease_id(task.lease_id());
  failure.set_permanent(true);
  failure.set_reason("cannot write /mnt/elsewhere/store/" + task.store_path() +
                     "/staging/transport/0.5: No space left on device");
  v1::FailReply fail_reply;
  ASSERT_TRUE(workers_->Fail(CallContext("").get(), failure, &fail_reply).ok());
  v1::JobId id;
  id.set_id(job.id());
  v1::Job failed;
  ASSERT_TRUE(jobs_->Get(CallContext("").get(), id, &failed).ok());
  EXPECT_EQ(failed.phase(), v1::PHASE_FAILED);
  EXPECT_THAT(failed.error(), HasSubstr("cannot write <store root>/" + task.store_path() +
                                        "/staging/transport/0.5: No space"));
  EXPECT_THAT(failed.error(), ::testing::Not(HasSubstr("/mnt/elsewhere")));
}

// Two coordinators on one data directory would diverge from its database.
TEST_F(GrpcTest, SecondCoordinatorOnTheSameDataDirIsRefused) {
  Start();
  auto second =
      Coordinator::Start({.listen_address = "", .data_dir = dir_.path()}, FakePlan, nullptr);
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(second.status().message(),
              HasSubstr(absl::StrCat("in use by another coordinator (pid ", ::getpid())));
  coordinator_.reset();  // its lock goes with it
  auto third =
      Coordinator::Start({.listen_address = "", .data_dir = dir_.path()}, FakePlan, nullptr);
  EXPECT_TRUE(third.ok()) << third.status();
}

// A partial store whose job never reached the database (a coordinator that
// died between planning and committing; a submit that failed on a full disk
// before submits were transactional) holds space and blocks its name: the
// next start removes it and keeps the unfinished jobs' own.
TEST_F(GrpcTest, StartRemovesPartialStoresOfNoUnfinishedJob) {
  Start();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  coordinator_.reset();
  const std::filesystem::path store = dir_.path() / "store";
  const std::filesystem::path live = store / ("." + job.store_path() + ".partial");
  const std::filesystem::path orphan = store / ".job-99.wbk.partial";
  std::filesystem::create_directories(live / "staging");
  std::filesystem::create_directories(orphan / "staging");
  Start();
  EXPECT_TRUE(std::filesystem::exists(live));
  EXPECT_FALSE(std::filesystem::exists(orphan));
}

TEST_F(GrpcTest, RestartedCoordinatorKnowsItsJobs) {
  Start();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  coordinator_.reset();
  Start();
  v1::JobId id;
  id.set_id(job.id());
  v1::Job again;
  ASSERT_TRUE(jobs_->Get(CallContext("").get(), id, &again).ok());
  EXPECT_EQ(again.phase(), v1::PHASE_QUEUED);
  EXPECT_EQ(again.tasks_total(), job.tasks_total());
  v1::Job second;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &second).ok());
  EXPECT_NE(second.id(), job.id());
}

TEST_F(GrpcTest, WatchStreamsLiveProgressAndEndsAtShutdown) {
  Start();
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  v1::JobId id;
  id.set_id(job.id());
  auto ctx = CallContext("", 20'000);
  auto stream = jobs_->Watch(ctx.get(), id);
  v1::JobEvent event;
  ASSERT_TRUE(stream->Read(&event));
  EXPECT_EQ(event.kind(), v1::EVENT_SUBMITTED);

  std::string worker;
  const v1::Task task = LeaseOne(&worker);
  v1::HeartbeatRequest hb;
  hb.set_worker_id(worker);
  v1::LeaseProgress* p = hb.add_leases();
  p->set_lease_id(task.lease_id());
  p->set_rays_traced(777);
  p->set_bytes_written(55);
  v1::HeartbeatReply hb_reply;
  ASSERT_TRUE(workers_->Heartbeat(CallContext("").get(), hb, &hb_reply).ok());
  EXPECT_EQ(hb_reply.renewed_lease_ids_size(), 1);
  bool progress = false;
  while (!progress && stream->Read(&event)) {
    progress = event.kind() == v1::EVENT_PROGRESS && event.rays_traced() == 777;
  }
  ASSERT_TRUE(progress);
  EXPECT_EQ(event.bytes_written(), 55);
  EXPECT_EQ(event.phase(), v1::PHASE_BAKING);
  EXPECT_EQ(event.tasks_total(), kTiles + kGroups + FinalizeShards(kGroups) + 1);

  // Shutdown ends open Watch streams instead of waiting for the job.
  const auto start = std::chrono::steady_clock::now();
  coordinator_->Shutdown();
  while (stream->Read(&event)) {
  }
  EXPECT_FALSE(stream->Finish().ok());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
}

TEST_F(GrpcTest, LeaseOfVanishedWorkerExpiresWithoutAnyCall) {
  Start("", 1 << 20, /*lease_seconds=*/0.2);
  v1::Job job;
  ASSERT_TRUE(Submit(testing::BuiltinRequest(), &job).ok());
  std::string worker;
  const v1::Task task = LeaseOne(&worker);
  EXPECT_EQ(task.kind(), v1::BAKE_TILE);
  EXPECT_EQ(task.index(), 0);
  EXPECT_EQ(task.attempt(), 1);
  EXPECT_EQ(task.request().light_res(), 32);
  v1::JobId id;
  id.set_id(job.id());
  v1::Job now;
  ASSERT_TRUE(jobs_->Get(CallContext("").get(), id, &now).ok());
  EXPECT_EQ(now.leased_tasks(), 1);
  // The coordinator's reaper returns the task; nobody calls meanwhile.
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  ASSERT_TRUE(jobs_->Get(CallContext("").get(), id, &now).ok());
  EXPECT_EQ(now.leased_tasks(), 0);
  std::string other;
  const v1::Task again = LeaseOne(&other);
  EXPECT_EQ(again.index(), 0);
  EXPECT_EQ(again.attempt(), 2);
}

TEST_F(GrpcTest, ServesTlsWhenGivenCertAndKey) {
  const auto cert = dir_.path() / "cert.pem", key = dir_.path() / "key.pem";
  const std::string cmd =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
      "-addext subjectAltName=DNS:localhost,IP:127.0.0.1 -keyout " +
      key.string() + " -out " + cert.string() + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) GTEST_SKIP() << "no openssl to make a test certificate";
  auto c = Coordinator::Start({.listen_address = "127.0.0.1:0",
                               .data_dir = dir_.path() / "data",
                               .tls_cert_path = cert,
                               .tls_key_path = key},
                              FakePlan, nullptr);
  ASSERT_TRUE(c.ok()) << c.status();
  std::ifstream in(cert);
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs.assign(std::istreambuf_iterator<char>(in), {});
  auto tls =
      v1::JobService::NewStub(grpc::CreateChannel((*c)->address(), grpc::SslCredentials(ssl)));
  v1::JobList list;
  EXPECT_TRUE(tls->List(CallContext("").get(), v1::ListRequest(), &list).ok());
  auto plain = v1::JobService::NewStub(
      grpc::CreateChannel((*c)->address(), grpc::InsecureChannelCredentials()));
  EXPECT_FALSE(plain->List(CallContext("", 2000).get(), v1::ListRequest(), &list).ok());
  auto half = Coordinator::Start({.data_dir = dir_.path() / "d2", .tls_cert_path = cert}, FakePlan,
                                 nullptr);
  EXPECT_EQ(half.status().code(), absl::StatusCode::kInvalidArgument);
}

// health_address: Kubernetes' grpc probe speaks plain text only, so a TLS
// coordinator offers the health service alone on a plain port; the job and
// worker services are not there (UNIMPLEMENTED), so no token crosses it.
TEST_F(GrpcTest, PlainHealthPortBesideTlsServesHealthOnly) {
  const auto cert = dir_.path() / "cert.pem", key = dir_.path() / "key.pem";
  const std::string cmd =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
      "-addext subjectAltName=DNS:localhost,IP:127.0.0.1 -keyout " +
      key.string() + " -out " + cert.string() + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) GTEST_SKIP() << "no openssl to make a test certificate";
  auto c = Coordinator::Start({.listen_address = "127.0.0.1:0",
                               .data_dir = dir_.path() / "data",
                               .tls_cert_path = cert,
                               .tls_key_path = key,
                               .health_address = "127.0.0.1:0"},
                              FakePlan, nullptr);
  ASSERT_TRUE(c.ok()) << c.status();
  ASSERT_NE((*c)->health_port(), 0);
  ASSERT_NE((*c)->health_port(), (*c)->port());
  auto plain = grpc::CreateChannel(absl::StrCat("127.0.0.1:", (*c)->health_port()),
                                   grpc::InsecureChannelCredentials());
  EXPECT_EQ(HealthCheck(plain, "").value_or("error"), kServing);
  EXPECT_EQ(HealthCheck(plain, kLivenessService).value_or("error"), kServing);
  EXPECT_EQ(HealthCheck(plain, "no.such.Service").status().code(), absl::StatusCode::kNotFound);
  v1::JobList list;
  EXPECT_EQ(v1::JobService::NewStub(plain)
                ->List(CallContext("").get(), v1::ListRequest(), &list)
                .error_code(),
            grpc::StatusCode::UNIMPLEMENTED);
  (*c)->Shutdown();
}

// The probe port on a full disk: its overall status follows the main port's
// (NOT_SERVING while the table cannot record a change: not ready), while
// the liveness service stays SERVING (a restart would not free the disk),
// and both serve again once the reaper's recovery commits.
TEST_F(GrpcTest, ProbePortIsNotReadyButAliveWhileTheDiskIsFull) {
  auto c = Coordinator::Start({.listen_address = "127.0.0.1:0",
                               .data_dir = dir_.path() / "data",
                               .health_address = "127.0.0.1:0",
                               .lease_seconds = 0.2},
                              FakePlan, nullptr);
  ASSERT_TRUE(c.ok()) << c.status();
  auto main_port = grpc::CreateChannel((*c)->address(), grpc::InsecureChannelCredentials());
  auto probe = grpc::CreateChannel(absl::StrCat("127.0.0.1:", (*c)->health_port()),
                                   grpc::InsecureChannelCredentials());
  LeaseTable& table = (*c)->table();
  ASSERT_TRUE(table.AddJob(table.ReserveJobId(), "", 1, testing::Plan(2, 1, "a.wbk")).ok());
  JobStore& store = (*c)->job_store();
  ASSERT_TRUE(store.LimitGrowthForTesting(0).ok());
  store.SetFullForTesting(true);
  // A refused commit stops the table; the reaper's reload must commit the
  // job's RESUMED event, which the full disk refuses too.
  EXPECT_EQ(table.AddJob(table.ReserveJobId(), "", 1, testing::Plan(2, 1, "b.wbk")).status().code(),
            absl::StatusCode::kResourceExhausted);
  const auto wait_for = [](const std::shared_ptr<grpc::Channel>& ch, const std::string& service,
                           const std::string& want) {
    for (int i = 0; i < 100; ++i) {
      if (HealthCheck(ch, service).value_or("") == want) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  };
  EXPECT_TRUE(wait_for(main_port, "", kNotServing));
  EXPECT_TRUE(wait_for(probe, "", kNotServing));
  EXPECT_EQ(HealthCheck(probe, kLivenessService).value_or("error"), kServing);
  ASSERT_TRUE(store.LimitGrowthForTesting(int64_t{1} << 30).ok());
  store.SetFullForTesting(false);
  EXPECT_TRUE(wait_for(probe, "", kServing));
  EXPECT_TRUE(wait_for(main_port, "", kServing));
  EXPECT_EQ(HealthCheck(probe, kLivenessService).value_or("error"), kServing);
  (*c)->Shutdown();
}

}  // namespace
}  // namespace wavebake
