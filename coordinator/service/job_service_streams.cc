// JobService streaming methods: Watch, UploadScene, ReadStore (DESIGN.md §4).
#include <algorithm>
#include <fstream>
#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "coordinator/service/job_service.h"
#include "coordinator/service/proto_convert.h"

namespace wavebake {
namespace {

// At most one live progress event per this many ms (heartbeats can be frequent).
constexpr int64_t kMinProgressIntervalMs = 200;

bool Stopping(const ServiceDeps& deps) { return deps.stopping && deps.stopping->load(); }

}  // namespace

// Replays the job's persisted events, then follows new ones and sends live
// progress between them, until the job ends (its last phase event is sent).
grpc::Status JobServiceImpl::Watch(grpc::ServerContext* context, const v1::JobId* request,
                                   grpc::ServerWriter<v1::JobEvent>* writer) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> id = ParseJobId(*request);
  if (!id.ok()) return Reply(id.status());
  int64_t seq = 0, last_progress_ms = 0;
  int64_t sent_rays = -1, sent_bytes = -1, sent_done = -1;
  v1::JobEvent event;
  for (;;) {
    if (context->IsCancelled()) return {grpc::StatusCode::CANCELLED, "watch cancelled"};
    if (Stopping(deps_)) return {grpc::StatusCode::UNAVAILABLE, "coordinator shutting down"};
    // A table that cannot persist (a full disk) will not see the job end.
    if (absl::Status broken = deps_.table->broken(); !broken.ok()) return Reply(broken);
    const uint64_t generation = deps_.table->generation();
    // Read the job before its events: a job seen ended has its last event stored.
    absl::StatusOr<JobInfo> info = deps_.table->Get(*id);
    if (!info.ok()) return Reply(info.status());
    for (;;) {
      absl::StatusOr<std::vector<EventRecord>> events = deps_.table->ReadEvents(*id, seq, 256);
      if (!events.ok()) return Reply(events.status());
      for (const EventRecord& e : *events) {
        ToProto(e, info->record, &event);
        event.set_message(deps_.client_paths(event.message()));
        if (!writer->Write(event)) return grpc::Status::OK;  // the client went away
        seq = e.seq;
      }
      if (events->size() < 256) break;
    }
    if (IsTerminal(info->record.phase)) return grpc::Status::OK;
    // Progress from the job as it is now: `info` was read before the events
    // just sent and may hold a phase older than theirs.
    info = deps_.table->Get(*id);
    if (!info.ok()) return Reply(info.status());
    if (IsTerminal(info->record.phase)) continue;  // its last events come first
    const int64_t now = SystemClock::Get()->NowMs();
    const bool changed = info->rays_traced != sent_rays || info->bytes_written != sent_bytes ||
                         info->tasks_done != sent_done;
    if (changed && now - last_progress_ms >= kMinProgressIntervalMs) {
      ProgressEvent(*info, seq, now, &event);
      if (!writer->Write(event)) return grpc::Status::OK;
      last_progress_ms = now;
      sent_rays = info->rays_traced;
      sent_bytes = info->bytes_written;
      sent_done = info->tasks_done;
    }
    deps_.table->WaitForChange(generation, changed ? kMinProgressIntervalMs : deps_.watch_poll_ms);
  }
}

grpc::Status JobServiceImpl::UploadScene(grpc::ServerContext* context,
                                         grpc::ServerReader<v1::SceneChunk>* reader,
                                         v1::SceneRef* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  std::unique_ptr<SceneUpload> upload;  // removes its temporary file unless finished
  std::string expected_sha;
  v1::SceneChunk chunk;
  while (reader->Read(&chunk)) {
    if (!upload) {
      absl::StatusOr<std::unique_ptr<SceneUpload>> begun =
          deps_.scenes->BeginUpload(chunk.file_name());
      if (!begun.ok()) return Reply(begun.status());
      upload = std::move(*begun);
      expected_sha = chunk.sha256();
    }
    if (absl::Status s = upload->Append(chunk.data()); !s.ok()) return Reply(s);
  }
  if (!upload) return {grpc::StatusCode::INVALID_ARGUMENT, "data: the upload sent no chunk"};
  absl::StatusOr<SceneRecord> rec = upload->Finish(expected_sha);
  if (!rec.ok()) return Reply(rec.status());
  reply->set_sha256(rec->sha256);
  reply->set_size(rec->size);
  reply->set_file_name(rec->file_name);
  return grpc::Status::OK;
}

grpc::Status JobServiceImpl::ReadStore(grpc::ServerContext* context, const v1::JobId* request,
                                       grpc::ServerWriter<v1::FileChunk>* writer) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> id = ParseJobId(*request);
  if (!id.ok()) return Reply(id.status());
  absl::StatusOr<JobInfo> info = deps_.table->Get(*id);
  if (!info.ok()) return Reply(info.status());
  if (info->record.phase != Phase::kDone) {
    return {grpc::StatusCode::FAILED_PRECONDITION,
            absl::StrCat("job ", *id, " is ", PhaseName(info->record.phase), ", not DONE")};
  }
  const std::filesystem::path dir = deps_.store_root / info->record.store_path;
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file()) files.push_back(it->path());
  }
  if (ec)
    return Reply(absl::InternalError(absl::StrCat("store ", dir.string(), ": ", ec.message())));
  std::sort(files.begin(), files.end());
  std::string buffer(static_cast<size_t>(deps_.chunk_bytes), '\0');
  v1::FileChunk chunk;
  for (const std::filesystem::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const int64_t size = static_cast<int64_t>(std::filesystem::file_size(file, ec));
    if (!in || ec) return Reply(absl::InternalError(absl::StrCat("cannot read ", file.string())));
    chunk.set_path(std::filesystem::relative(file, dir).generic_string());
    chunk.set_file_size(size);
    int64_t offset = 0;
    do {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const int64_t n = in.gcount();
      chunk.set_offset(offset);
      chunk.set_data(buffer.data(), static_cast<size_t>(n));
      offset += n;
      chunk.set_last(offset >= size || n == 0);
      if (context->IsCancelled() || !writer->Write(chunk)) return grpc::Status::OK;
    } while (!chunk.last());
  }
  return grpc::Status::OK;
}

}  // namespace wavebake
