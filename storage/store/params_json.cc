#include "storage/store/params_json.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_param_words.h"
#include "core/bake/bake_params_io.h"

namespace wavebake {
namespace {

using nlohmann::json;

absl::Status Bad(std::string_view field, std::string_view why) {
  return absl::InvalidArgumentError(
      absl::StrCat("params.", std::string(field), ": ", std::string(why)));
}

// A row's value as .zattrs hold it: numbers as JSON numbers (a number's word
// for 0 as that word: "bits": "auto"), everything else as its words (a
// flag-only switch as a JSON bool).
template <class T>
json ValueOf(const params::Number<T>& row, const BakeParams& p) {
  const T v = p.*row.field;
  return v == row.special_value && row.special_is_word ? json(std::string(row.special)) : json(v);
}
inline json ValueOf(const params::Switch& row, const BakeParams& p) {
  return params::InWords(row) ? json(params::Spell(row, p)) : json(p.*row.field);
}
template <class Row>
json ValueOf(const Row& row, const BakeParams& p) {
  return params::Spell(row, p);
}

// The value a store without the row means (Record::kUnlessAbsent).
template <class Row>
json AbsentOf(const Row& row) {
  return ValueOf(row, BakeParams{});
}
inline json AbsentOf(const params::Switch& row) {
  return params::InWords(row) ? json(std::string(row.absent ? row.yes : row.no)) : json(row.absent);
}

// A field of a record, or for one the record leaves out the value its absence
// means (Record::kUnlessAbsent), so that a refusal names it ("0 there").
json FieldOrAbsent(const json& record, const std::string& field) {
  if (record.contains(field)) return record[field];
  json absent = "(absent)";
  params::ForEach([&](const auto& row) {
    if (row.info.name == field && row.info.record == params::Record::kUnlessAbsent &&
        !row.info.recorded_if)
      absent = AbsentOf(row);
  });
  return absent;
}

template <class T>
absl::Status Read(const params::Number<T>& row, const json& v, BakeParams& p) {
  if (row.special_is_word && v == row.special) {
    p.*row.field = row.special_value;
    return absl::OkStatus();
  }
  if constexpr (std::is_same_v<T, uint64_t>) {
    if (!v.is_number_unsigned()) return Bad(row.info.name, "missing or not an unsigned integer");
  } else if constexpr (std::is_integral_v<T>) {
    if (!v.is_number_integer()) return Bad(row.info.name, "missing or not an integer");
  } else if (!v.is_number()) {
    return Bad(row.info.name, "missing or not a number");
  }
  if constexpr (std::is_integral_v<T>)
    p.*row.field = v.get<T>();
  else
    p.*row.field = static_cast<T>(v.get<double>());
  return absl::OkStatus();
}
template <class Row>
absl::Status Read(const Row& row, const json& v, BakeParams& p) {
  if (!v.is_string()) return Bad(row.info.name, "missing or not a string");
  if (absl::Status s = params::ParseInto(row, v.get<std::string>(), p); !s.ok())
    return absl::InvalidArgumentError(absl::StrCat("params.", s.message()));
  return absl::OkStatus();
}

}  // namespace

json ToJson(const BakeParams& p) {
  json j = json::object();
  params::ForEach([&](const auto& row) {
    if (row.info.record == params::Record::kNever) return;
    json v = ValueOf(row, p);
    if (row.info.record == params::Record::kUnlessAbsent &&
        (row.info.recorded_if ? !row.info.recorded_if(p) : v == AbsentOf(row)))
      return;
    j[std::string(row.info.name)] = std::move(v);
  });
  return j;
}

json ToJson(const BakeParams& p, params::Stage stage) {
  json j = json::object();
  params::ForEach([&](const auto& row) {
    if (row.info.stage == stage) j[std::string(row.info.name)] = ValueOf(row, p);
  });
  return j;
}

absl::StatusOr<BakeParams> BakeParamsFromJson(const json& j) {
  if (!j.is_object()) return absl::InvalidArgumentError("params: not an object");
  BakeParams p;
  absl::Status status = absl::OkStatus();
  params::ForEach([&](const auto& row) {
    if (!status.ok() || row.info.record == params::Record::kNever) return;
    const std::string name(row.info.name);
    if (j.contains(name))
      status = Read(row, j[name], p);
    else if (row.info.record == params::Record::kUnlessAbsent)
      status = Read(row, AbsentOf(row), p);
    else
      status = Read(row, json(nullptr), p);  // "missing or not ..."
  });
  if (!status.ok()) return status;
  if (absl::Status s = ValidateBakeParams(p); !s.ok())
    return absl::InvalidArgumentError(absl::StrCat("params.", s.message()));
  return p;
}

std::string FirstParameterDifference(const nlohmann::json& have, const nlohmann::json& want) {
  constexpr char kWhy[] = ": an update keeps every parameter but the scene";
  for (const auto& [field, value] : want.items()) {
    const json there = FieldOrAbsent(have, field);
    if (there == value) continue;
    return absl::StrCat("parameter ", field, " is ", there.dump(), " there and ", value.dump(),
                        " here", kWhy);
  }
  for (const auto& [field, value] : have.items()) {
    if (want.contains(field)) continue;  // compared above
    const json here = FieldOrAbsent(want, field);
    if (here != value)
      return absl::StrCat("parameter ", field, " is ", value.dump(), " there and ", here.dump(),
                          " here", kWhy);
  }
  return "";
}

}  // namespace wavebake
