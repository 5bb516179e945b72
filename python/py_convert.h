#pragma once
// Between Python objects and the project's types: protobuf messages as dicts
// (the one JSON shape of driver/jobs/job_json.h), BakeRequest fields from keyword
// arguments, nlohmann::json as Python values, absl errors as exceptions.
#include <google/protobuf/message.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "wavebake.pb.h"

namespace wavebake::python {

namespace py = pybind11;

// Every field, set or not, so a dict has the same keys each time; enum
// values without their prefix ("DONE"), numbers as numbers.
py::dict MessageToDict(const google::protobuf::Message& message);

// light_res=16, layout="camera:32x32", seed=7, ...: the BakeRequest fields by
// name. An unknown name or a value of the wrong type raises ValueError /
// TypeError naming the argument.
void SetRequestFields(v1::BakeRequest& request, const py::kwargs& fields);

py::object JsonToPython(const nlohmann::json& j);

// Raises the wavebake.Error subclass of the status's code (InvalidArgument,
// a ValueError; NotFound, a FileNotFoundError; ...) with the status's
// message, which names the bad input.
[[noreturn]] void Raise(const absl::Status& status);
// wavebake.InvalidArgument(message): an argument the binding itself refuses.
[[noreturn]] void RaiseInvalid(const std::string& message);

template <typename T>
T Unwrap(absl::StatusOr<T> value) {
  if (!value.ok()) Raise(value.status());
  return *std::move(value);
}
inline void Check(const absl::Status& status) {
  if (!status.ok()) Raise(status);
}

}  // namespace wavebake::python
