#pragma once
// The bake parameters a user spells in words (the command line's flags, a
// request's string fields, the store's .zattrs): for every row of the table
// (core/bake/bake_param_table.h) that has a spelling, the words of a value
// and the value of words, so that every front end, the RPC and the store
// read and write the same strings.
#include <charconv>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/bake/bake_param_table.h"

namespace wavebake {

struct BakeParamWords {
  // Words by parameter name ("column_mode" → "2d"); a name not given keeps
  // the value of the numbers ParseBakeParamWords starts from.
  std::map<std::string, std::string, std::less<>> words;
  bool allow_uv_overlap = false;  // uv layouts: the layout's ",allow-overlap"
};

// `numbers` with the words parsed into it, then validated as a whole. Errors
// name the field (e.g. "column_mode: unknown value 'fast' (adaptive|full|2d)").
absl::StatusOr<BakeParams> ParseBakeParamWords(BakeParams numbers, const BakeParamWords& words);

namespace params {

// Whether a row is spelled in words (else it is a plain number or a flag).
template <class T>
bool InWords(const Number<T>& r) {
  return r.special_is_word;
}
template <class E>
bool InWords(const Words<E>&) {
  return true;
}
inline bool InWords(const Switch& r) { return !r.yes.empty(); }
template <class T>
bool InWords(const Spelled<T>&) {
  return true;
}

// The spelling of a row's value in `p` (a switch's effective value).
template <class T>
std::string Spell(const Number<T>& r, const BakeParams& p) {
  const T v = p.*r.field;
  return v == r.special_value && r.special_is_word ? std::string(r.special) : absl::StrCat(v);
}
template <class E>
std::string Spell(const Words<E>& r, const BakeParams& p) {
  return std::string(WordOf(r.words, p.*r.field));
}
inline std::string Spell(const Switch& r, const BakeParams& p) {
  const bool on = r.effective ? r.effective(p) : p.*r.field;
  return std::string(on ? r.yes : r.no);
}
template <class T>
std::string Spell(const Spelled<T>& r, const BakeParams& p) {
  return r.print(p.*r.field);
}

inline absl::Status BadWords(const Info& info, std::string_view s, std::string_view want) {
  return absl::InvalidArgumentError(
      absl::StrCat(std::string(info.name), ": '", std::string(s), "' is not ", std::string(want)));
}

// `s` parsed into the row's field of `p`; the error names the field.
template <class T>
absl::Status ParseInto(const Number<T>& r, std::string_view s, BakeParams& p) {
  if (r.special_is_word && s == r.special) {
    p.*r.field = r.special_value;
    return absl::OkStatus();
  }
  T v{};
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  // The special value is spelled by its word, so its number is refused.
  if (ec != std::errc() || ptr != s.data() + s.size() ||
      (r.special_is_word && v == r.special_value))
    return BadWords(
        r.info, s,
        absl::StrCat(static_cast<long long>(r.lo), "..", static_cast<long long>(r.hi),
                     r.special_is_word ? absl::StrCat(" or ", std::string(r.special)) : ""));
  p.*r.field = v;
  return absl::OkStatus();
}
template <class E>
std::string Joined(WordList<E> words) {
  std::vector<std::string> all;
  for (const auto& [w, v] : words) all.emplace_back(w);
  return absl::StrJoin(all, "|");
}

// The value `s` spells in `words`; the error names `field` and the words.
template <class E>
absl::StatusOr<E> ParseWord(std::string_view field, WordList<E> words, std::string_view s) {
  for (const auto& [w, v] : words)
    if (s == w) return v;
  return absl::InvalidArgumentError(absl::StrCat(std::string(field), ": unknown value '",
                                                 std::string(s), "' (", Joined(words), ")"));
}

template <class E>
absl::Status ParseInto(const Words<E>& r, std::string_view s, BakeParams& p) {
  absl::StatusOr<E> v = ParseWord(r.info.name, r.words, s);
  if (!v.ok()) return v.status();
  p.*r.field = *v;
  return absl::OkStatus();
}
inline absl::Status ParseInto(const Switch& r, std::string_view s, BakeParams& p) {
  if (s != r.yes && s != r.no)
    return BadWords(r.info, s, absl::StrCat(std::string(r.yes), " or ", std::string(r.no)));
  p.*r.field = s == r.yes;
  return absl::OkStatus();
}
template <class T>
absl::Status ParseInto(const Spelled<T>& r, std::string_view s, BakeParams& p) {
  absl::StatusOr<T> v = r.parse(s);
  if (!v.ok()) return v.status();  // the parsers name their field
  p.*r.field = *std::move(v);
  return absl::OkStatus();
}

}  // namespace params
}  // namespace wavebake
