#include "driver/jobs/job_json.h"

#include <google/protobuf/reflection.h>

#include <string_view>

#include "absl/strings/escaping.h"

namespace wavebake::driver {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

nlohmann::json FieldJson(const Message& m, const Reflection& r, const FieldDescriptor* f, int i) {
  const bool rep = f->is_repeated();
  switch (f->cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      return rep ? r.GetRepeatedInt32(m, f, i) : r.GetInt32(m, f);
    case FieldDescriptor::CPPTYPE_INT64:
      return rep ? r.GetRepeatedInt64(m, f, i) : r.GetInt64(m, f);
    case FieldDescriptor::CPPTYPE_UINT32:
      return rep ? r.GetRepeatedUInt32(m, f, i) : r.GetUInt32(m, f);
    case FieldDescriptor::CPPTYPE_UINT64:
      return rep ? r.GetRepeatedUInt64(m, f, i) : r.GetUInt64(m, f);
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return rep ? r.GetRepeatedDouble(m, f, i) : r.GetDouble(m, f);
    case FieldDescriptor::CPPTYPE_FLOAT:
      return rep ? r.GetRepeatedFloat(m, f, i) : r.GetFloat(m, f);
    case FieldDescriptor::CPPTYPE_BOOL:
      return rep ? r.GetRepeatedBool(m, f, i) : r.GetBool(m, f);
    case FieldDescriptor::CPPTYPE_ENUM:
      return EnumValueName(rep ? *r.GetRepeatedEnum(m, f, i) : *r.GetEnum(m, f));
    case FieldDescriptor::CPPTYPE_STRING: {
      const std::string s = rep ? r.GetRepeatedString(m, f, i) : r.GetString(m, f);
      // Bytes as the proto JSON mapping has them: base64.
      return f->type() == FieldDescriptor::TYPE_BYTES ? absl::Base64Escape(s) : s;
    }
    case FieldDescriptor::CPPTYPE_MESSAGE:
      return MessageJson(rep ? r.GetRepeatedMessage(m, f, i) : r.GetMessage(m, f));
  }
  return nullptr;
}

}  // namespace

std::string EnumValueName(const google::protobuf::EnumValueDescriptor& value) {
  const google::protobuf::EnumDescriptor& e = *value.type();
  std::string_view prefix = e.value(0)->name();
  for (int i = 1; i < e.value_count(); ++i) {
    const std::string& name = e.value(i)->name();
    size_t n = 0;
    while (n < prefix.size() && n < name.size() && prefix[n] == name[n]) ++n;
    prefix = prefix.substr(0, n);
  }
  const size_t end = prefix.rfind('_');
  const std::string& name = value.name();
  return end == std::string_view::npos ? name : name.substr(end + 1);
}

nlohmann::json MessageJson(const Message& m) {
  const Reflection& r = *m.GetReflection();
  const google::protobuf::Descriptor& d = *m.GetDescriptor();
  nlohmann::json out = nlohmann::json::object();
  for (int i = 0; i < d.field_count(); ++i) {
    const FieldDescriptor* f = d.field(i);
    if (f->is_repeated()) {
      nlohmann::json list = nlohmann::json::array();
      for (int k = 0; k < r.FieldSize(m, f); ++k) list.push_back(FieldJson(m, r, f, k));
      out[f->name()] = std::move(list);
    } else if ((f->containing_oneof() || f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) &&
               !r.HasField(m, f)) {
      continue;  // the unset branches of a oneof (scene source, seed presence), unset messages
    } else {
      out[f->name()] = FieldJson(m, r, f, 0);
    }
  }
  return out;
}

}  // namespace wavebake::driver
