#pragma once
// A job as JSON, in the one shape every reader of a job gets (`wavebake
// status --json`, the monitor's /api/jobs, Python's dicts): the gRPC message
// (proto/wavebake.proto) with its .proto field names, every field present
// (an unset branch of a oneof left out), numbers as JSON numbers (int64 too:
// ray counts and epoch milliseconds stay far below 2^53, where a double stops
// being exact) and enum values without their type's prefix ("DONE", not
// "PHASE_DONE"; "SUBMITTED", not "EVENT_SUBMITTED").
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <nlohmann/json.hpp>
#include <string>

namespace wavebake::driver {

nlohmann::json MessageJson(const google::protobuf::Message& message);

// "PHASE_DONE" -> "DONE": the name less the longest '_'-ended prefix that
// every value of its enum shares (none for BAKE_TILE / FINALIZE / ...).
std::string EnumValueName(const google::protobuf::EnumValueDescriptor& value);

}  // namespace wavebake::driver
