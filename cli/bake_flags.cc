#include "cli/bake_flags.h"

#include <string>

namespace wavebake::cli {
namespace {

// One flag per row of the table of bake parameters (core/bake/bake_param_table.h):
// numbers bind to BakeParams, words to BakeParamWords (parsed with the rest).
struct AddFlag {
  CLI::App& cmd;
  BakeFlags& flags;

  template <class Row>
  void operator()(const Row& row) {
    if (row.info.flag.empty()) return;
    const std::string flag(row.info.flag), help(row.info.help);
    if (params::InWords(row)) {
      std::string& word = flags.words.words[std::string(row.info.name)];
      word = params::Spell(row, BakeParams{});
      cmd.add_option(flag, word, help)->capture_default_str();
    } else {
      Bind(row, flag, help);
    }
  }
  template <class T>
  void Bind(const params::Number<T>& row, const std::string& flag, const std::string& help) {
    cmd.add_option(flag, flags.params.*row.field, help)->capture_default_str();
  }
  void Bind(const params::Switch& row, const std::string& flag, const std::string& help) {
    cmd.add_flag(flag, flags.params.*row.field, help);
  }
  template <class Row>
  void Bind(const Row&, const std::string&, const std::string&) {}  // always in words
};

}  // namespace

void AddBakeFlags(CLI::App& cmd, BakeFlags& flags) {
  params::ForEach(AddFlag{cmd, flags});
  cmd.add_flag("--allow-uv-overlap", flags.words.allow_uv_overlap,
               "uv layouts: bake an atlas whose charts overlap (each texel then takes its "
               "nearest triangle)");
}

}  // namespace wavebake::cli
