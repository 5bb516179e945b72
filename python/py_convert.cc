#include "python/py_convert.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <string>

#include "absl/strings/str_cat.h"
#include "driver/jobs/job_json.h"

namespace wavebake::python {

using google::protobuf::FieldDescriptor;
using google::protobuf::Reflection;

py::dict MessageToDict(const google::protobuf::Message& m) {
  return JsonToPython(driver::MessageJson(m));
}

void SetRequestFields(v1::BakeRequest& request, const py::kwargs& fields) {
  const google::protobuf::Descriptor& d = *request.GetDescriptor();
  const Reflection& r = *request.GetReflection();
  for (const auto& [key, value] : fields) {
    const std::string name = py::str(key);
    const FieldDescriptor* f = d.FindFieldByName(name);
    if (!f || f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      RaiseInvalid(absl::StrCat(name, ": not a bake parameter (BakeRequest field)"));
    }
    try {
      switch (f->cpp_type()) {
        case FieldDescriptor::CPPTYPE_INT32:
          r.SetInt32(&request, f, value.cast<int32_t>());
          break;
        case FieldDescriptor::CPPTYPE_UINT64:
          r.SetUInt64(&request, f, value.cast<uint64_t>());
          break;
        case FieldDescriptor::CPPTYPE_DOUBLE:
          r.SetDouble(&request, f, value.cast<double>());
          break;
        case FieldDescriptor::CPPTYPE_BOOL:
          r.SetBool(&request, f, value.cast<bool>());
          break;
        case FieldDescriptor::CPPTYPE_STRING:
          r.SetString(&request, f, value.cast<std::string>());
          break;
        default:
          RaiseInvalid(absl::StrCat(name, ": cannot be set from Python"));
      }
    } catch (const py::cast_error&) {
      throw py::type_error(absl::StrCat(name, ": ", std::string(py::str(py::type::of(value))),
                                        " is not the field's type"));
    }
  }
}

py::object JsonToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

void Raise(const absl::Status& status) {
  // wavebake.Error's subclass for the code (python/wavebake/__init__.py);
  // the class names the kind, so the message is the status's alone.
  py::object cls =
      py::module_::import("wavebake").attr("_error_class")(static_cast<int>(status.code()));
  PyErr_SetObject(cls.ptr(), py::str(std::string(status.message())).ptr());
  throw py::error_already_set();
}

void RaiseInvalid(const std::string& message) { Raise(absl::InvalidArgumentError(message)); }

}  // namespace wavebake::python
