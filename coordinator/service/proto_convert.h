#pragma once
// Between the coordinator's plain records and wavebake.v1 messages, and from
// absl::Status (inside) to grpc::Status (the RPC boundary).
#include <grpcpp/support/status.h>

#include "absl/status/status.h"
#include "coordinator/scheduling/lease_table.h"
#include "wavebake.pb.h"

namespace wavebake {

grpc::Status ToGrpc(const absl::Status& status);

void ToProto(const JobInfo& info, v1::Job* job);
// `job` is the event's job: its plan gives the event's phase_tasks_*.
void ToProto(const EventRecord& event, const JobRecord& job, v1::JobEvent* out);
// A live progress snapshot of a job (EVENT_PROGRESS, not persisted).
void ProgressEvent(const JobInfo& info, int64_t last_seq, int64_t now_ms, v1::JobEvent* out);
// The task a worker receives; false if the stored request does not parse.
bool ToProto(const LeaseGrant& grant, v1::Task* task);

}  // namespace wavebake
