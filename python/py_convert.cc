#include "python/py_convert.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <string>

#include "absl/strings/str_cat.h"

namespace wavebake::python {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

py::object Scalar(const Message& m, const Reflection& r, const FieldDescriptor* f) {
  switch (f->cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      return py::int_(r.GetInt32(m, f));
    case FieldDescriptor::CPPTYPE_INT64:
      return py::int_(r.GetInt64(m, f));
    case FieldDescriptor::CPPTYPE_UINT32:
      return py::int_(r.GetUInt32(m, f));
    case FieldDescriptor::CPPTYPE_UINT64:
      return py::int_(r.GetUInt64(m, f));
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return py::float_(r.GetDouble(m, f));
    case FieldDescriptor::CPPTYPE_FLOAT:
      return py::float_(r.GetFloat(m, f));
    case FieldDescriptor::CPPTYPE_BOOL:
      return py::bool_(r.GetBool(m, f));
    case FieldDescriptor::CPPTYPE_ENUM:
      return py::str(r.GetEnum(m, f)->name());
    case FieldDescriptor::CPPTYPE_STRING:
      if (f->type() == FieldDescriptor::TYPE_BYTES) return py::bytes(r.GetString(m, f));
      return py::str(r.GetString(m, f));
    case FieldDescriptor::CPPTYPE_MESSAGE:
      return MessageToDict(r.GetMessage(m, f));
  }
  return py::none();
}

py::object Repeated(const Message& m, const Reflection& r, const FieldDescriptor* f) {
  py::list out;
  for (int i = 0; i < r.FieldSize(m, f); ++i) {
    if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      out.append(MessageToDict(r.GetRepeatedMessage(m, f, i)));
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_STRING) {
      out.append(py::str(r.GetRepeatedString(m, f, i)));
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_INT32) {
      out.append(py::int_(r.GetRepeatedInt32(m, f, i)));
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_INT64) {
      out.append(py::int_(r.GetRepeatedInt64(m, f, i)));
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
      out.append(py::float_(r.GetRepeatedDouble(m, f, i)));
    }
  }
  return out;
}

}  // namespace

py::dict MessageToDict(const Message& m) {
  const Reflection& r = *m.GetReflection();
  const google::protobuf::Descriptor& d = *m.GetDescriptor();
  py::dict out;
  for (int i = 0; i < d.field_count(); ++i) {
    const FieldDescriptor* f = d.field(i);
    if (f->is_repeated()) {
      out[py::str(f->name())] = Repeated(m, r, f);
    } else if (f->containing_oneof() && !r.HasField(m, f)) {
      continue;  // the unset branches of a oneof (scene source, seed presence)
    } else {
      out[py::str(f->name())] = Scalar(m, r, f);
    }
  }
  return out;
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
