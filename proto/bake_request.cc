#include "proto/bake_request.h"

#include <cmath>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"
#include "core/bake/bake_param_words.h"
#include "core/bake/bake_params_io.h"

namespace wavebake {
namespace {

absl::Status Bad(absl::string_view field, absl::string_view why) {
  return absl::InvalidArgumentError(absl::StrCat(field, ": ", why));
}

// The spelling is the core's (core/layouts/layout.h); the request keeps it as given
// ("camera" stays "camera", not "camera:64x64"), since the store records it.
absl::Status CheckScene(v1::BakeRequest& r) {
  const v1::SceneSource& scene = r.scene();
  switch (scene.source_case()) {
    case v1::SceneSource::kBuiltin: {
      const std::string name = BuiltinSceneName(r);
      if (name.empty() || name.size() > 64 ||
          name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != name.npos) {
        return Bad("scene.builtin", absl::StrCat("\"", scene.builtin(), "\" is not builtin:NAME"));
      }
      return absl::OkStatus();
    }
    case v1::SceneSource::kUploaded: {
      const std::string& sha = scene.uploaded().sha256();
      if (sha.size() != 64 || sha.find_first_not_of("0123456789abcdef") != sha.npos) {
        return Bad("scene.uploaded.sha256", "must be 64 lowercase hex digits");
      }
      return absl::OkStatus();
    }
    default:
      return Bad("scene", "missing: give a builtin:NAME or an uploaded SceneRef");
  }
}

absl::Status CheckOutputName(v1::BakeRequest& r) {
  const std::string& name = r.output_name();
  if (name.empty()) return absl::OkStatus();  // the coordinator names it after the job
  if (name.size() > 128 || name.front() == '.' ||
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") !=
          name.npos) {
    return Bad(
        "output_name",
        absl::StrCat("\"", name, "\" must be 1..128 of [A-Za-z0-9._-], not starting with '.'"));
  }
  return absl::OkStatus();
}

absl::Status CheckMaxAttempts(v1::BakeRequest& r) {
  if (r.max_attempts() == 0) r.set_max_attempts(kDefaultMaxAttempts);
  if (r.max_attempts() < 1 || r.max_attempts() > 100) {
    return Bad("max_attempts", absl::StrCat(r.max_attempts(), " is not in 1..100"));
  }
  return absl::OkStatus();
}

using google::protobuf::FieldDescriptor;

// The request's field of a table row: the same name (core/bake/bake_param_table.h;
// BakeParamTableTest checks that every row with in_request has one of a
// matching type).
const FieldDescriptor* FieldOf(const params::Info& info) {
  return v1::BakeRequest::descriptor()->FindFieldByName(std::string(info.name));
}

// Every table row between a request and BakeParams: numbers as numbers
// (proto3's unset 0 takes the default where the row says so; the seed has
// presence, since 0 is a seed), everything spelled in words as its words
// (an empty string takes the default).
struct RowsFromRequest {
  const v1::BakeRequest& r;
  BakeParams& p;
  absl::Status status = absl::OkStatus();

  template <class T>
  void operator()(const params::Number<T>& row) {
    const FieldDescriptor* f = FieldOf(row.info);
    if (!status.ok() || !row.info.in_request || f == nullptr) return;
    const google::protobuf::Reflection& refl = *r.GetReflection();
    if (f->has_presence() && !refl.HasField(r, f)) return;  // the default
    double v = 0;
    switch (f->cpp_type()) {
      case FieldDescriptor::CPPTYPE_INT32:
        v = refl.GetInt32(r, f);
        break;
      case FieldDescriptor::CPPTYPE_UINT64: {
        p.*row.field = static_cast<T>(refl.GetUInt64(r, f));  // 64 bits do not fit a double
        return;
      }
      case FieldDescriptor::CPPTYPE_DOUBLE:
        v = refl.GetDouble(r, f);
        break;
      default:
        status = Bad(std::string(row.info.name), "the request's field is not a number");
        return;
    }
    if (v == 0 && row.unset_is_default) return;
    p.*row.field = static_cast<T>(v);
  }
  void operator()(const params::Switch& row) {
    const FieldDescriptor* f = FieldOf(row.info);
    if (!status.ok() || f == nullptr) return;
    if (f->cpp_type() == FieldDescriptor::CPPTYPE_BOOL) {
      p.*row.field = r.GetReflection()->GetBool(r, f);
      return;
    }
    Words(row);
  }
  template <class Row>
  void operator()(const Row& row) {
    if (status.ok() && FieldOf(row.info) != nullptr) Words(row);
  }
  template <class Row>
  void Words(const Row& row) {
    const std::string s = r.GetReflection()->GetString(r, FieldOf(row.info));
    if (!s.empty()) status = params::ParseInto(row, s, p);
  }
};

struct RowsToRequest {
  const BakeParams& p;
  v1::BakeRequest& r;

  template <class T>
  void operator()(const params::Number<T>& row) {
    const FieldDescriptor* f = FieldOf(row.info);
    if (!row.info.in_request || f == nullptr) return;
    const google::protobuf::Reflection& refl = *r.GetReflection();
    const T v = p.*row.field;
    switch (f->cpp_type()) {
      case FieldDescriptor::CPPTYPE_INT32:
        refl.SetInt32(&r, f, static_cast<int32_t>(v));
        break;
      case FieldDescriptor::CPPTYPE_UINT64:
        refl.SetUInt64(&r, f, static_cast<uint64_t>(v));
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        refl.SetDouble(&r, f, static_cast<double>(v));
        break;
      default:
        break;
    }
  }
  void operator()(const params::Switch& row) {
    const FieldDescriptor* f = FieldOf(row.info);
    if (f == nullptr) return;
    if (f->cpp_type() == FieldDescriptor::CPPTYPE_BOOL)
      r.GetReflection()->SetBool(&r, f, p.*row.field);
    else
      r.GetReflection()->SetString(&r, f, params::Spell(row, p));
  }
  template <class Row>
  void operator()(const Row& row) {
    if (const FieldDescriptor* f = FieldOf(row.info); f != nullptr)
      r.GetReflection()->SetString(&r, f, params::Spell(row, p));
  }
};

// The core parameters of a request whose fields each parse.
absl::StatusOr<BakeParams> ParamsOf(const v1::BakeRequest& r) {
  BakeParams p;
  RowsFromRequest rows{r, p};
  params::ForEach(rows);
  if (!rows.status.ok()) return rows.status;
  return p;
}

}  // namespace

std::string BuiltinSceneName(const v1::BakeRequest& request) {
  if (!request.scene().has_builtin()) return {};
  absl::string_view name = request.scene().builtin();
  absl::ConsumePrefix(&name, "builtin:");
  return std::string(name);
}

absl::Status NormalizeBakeRequest(v1::BakeRequest& r) {
  const bool refine_unset = r.refine().empty();
  for (absl::Status s : {CheckScene(r), CheckMaxAttempts(r), CheckOutputName(r)}) {
    if (!s.ok()) return s;
  }
  absl::StatusOr<BakeParams> p = ParamsOf(r);
  if (!p.ok()) return p.status();
  // Refinement follows the cube's faces and integrates cosines: a plane
  // domain and a visibility transport default to brute force and cannot ask
  // for refinement.
  if (p->light_domain.is_plane() || p->transport == Transport::kVisibility) {
    if (!refine_unset && p->refine)
      return Bad("refine", p->light_domain.is_plane()
                               ? "\"on\" needs the cube light domain (plane domains trace "
                                 "every texel)"
                               : "\"on\" needs the diffuse transport (visibility rows are "
                                 "traced by brute force)");
    p->refine = false;
  }
  if (absl::Status s = ValidateBakeParams(*p); !s.ok()) return s;
  // The request shows the effective parameters: every default filled in,
  // the layout as it was spelled.
  const std::string layout = r.layout();
  RowsToRequest rows{*p, r};
  params::ForEach(rows);
  if (!layout.empty()) r.set_layout(layout);
  return absl::OkStatus();
}

absl::StatusOr<BakeParams> ToBakeParams(const v1::BakeRequest& request) {
  v1::BakeRequest r = request;
  if (absl::Status s = NormalizeBakeRequest(r); !s.ok()) return s;
  return ParamsOf(r);
}

v1::BakeRequest ToBakeRequest(const BakeParams& p) {
  v1::BakeRequest r;
  RowsToRequest rows{p, r};
  params::ForEach(rows);
  return r;
}

std::string PartialStorePath(const std::string& store_path) {
  const std::filesystem::path p(store_path);
  return (p.parent_path() / absl::StrCat(".", p.filename().string(), ".partial")).string();
}

}  // namespace wavebake
