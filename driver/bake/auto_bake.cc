#include "driver/bake/auto_bake.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <memory>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "driver/bake/embedded_bake.h"
#include "driver/eval/reference_measure.h"
#include "storage/files/scoped_dir.h"
#include "storage/zarr/zarr_group.h"
#include "worker/columns/publish_store.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/recode.h"

namespace wavebake::driver {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

int64_t DirectoryBytes(const std::filesystem::path& dir) {
  int64_t bytes = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) bytes += static_cast<int64_t>(e.file_size());
  return bytes;
}

void Say(const AutoBakeOptions& options, const char* format, ...)
    __attribute__((format(printf, 2, 3)));
void Say(const AutoBakeOptions& options, const char* format, ...) {
  if (!options.on_message) return;
  char line[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof line, format, args);
  va_end(args);
  options.on_message(line);
}

using Measures = std::vector<std::unique_ptr<ReferenceMeasure>>;

absl::StatusOr<Measures> MakeMeasures(const std::string& scene, const BakeParams& base,
                                      const AutoBakeOptions& options) {
  // The reference's own error inflates every measured e_tot (e² + SE²):
  // keeping it below E/5 bounds that to 2 % of E; it is not subtracted, so
  // the measurements err on the safe side.
  const double target_se = std::min(0.002, options.search.target_error / 5);
  Measures measures;
  for (const std::string& env : options.envs) {
    Say(options, "tracing the reference under %s (target rel SE %.4f)", env.c_str(), target_se);
    absl::StatusOr<std::unique_ptr<ReferenceMeasure>> measure =
        ReferenceMeasure::Create(scene, base, env, target_se);
    if (!measure.ok()) return measure.status();
    const ReferenceResult& r = (*measure)->reference();
    Say(options, "reference: %d samples, rel SE %.5f, %.1f Mrays, %.1f s", (*measure)->samples(),
        r.rel_se, r.rays / 1e6, r.seconds);
    measures.push_back(*std::move(measure));
  }
  return measures;
}

double Worst(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

std::string EnvName(const std::string& env) {
  return std::filesystem::path(env).filename().string();
}

// One traced light resolution: its context (column parameters set per
// candidate) and the trace directory, removed when the search moves on.
struct Trace {
  int light_res = 0;
  std::unique_ptr<BakeContext> ctx;
  std::filesystem::path dir;
};

int Threads(const AutoBakeOptions& options) {
  return options.workers > 0 ? options.workers
                             : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

absl::Status TraceResolution(const std::string& scene, BakeParams params, int light_res,
                             const std::filesystem::path& dir, const AutoBakeOptions& options,
                             AutoBakeReport& report, Trace& trace) {
  const auto t0 = Clock::now();
  params.light_res = light_res;
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext(scene, params);
  if (!ctx.ok()) return ctx.status();
  trace = {light_res, *std::move(ctx), dir / absl::StrCat("trace-N", light_res)};
  const int tiles = trace.ctx->plan.all_tiles();
  int reported = 0;  // quarters
  absl::StatusOr<uint64_t> rays = TraceStaging(
      *trace.ctx, trace.dir,
      {.threads = Threads(options),
       .cancel = options.interrupted,
       .on_tile = [&](int done, uint64_t so_far) {
         if (tiles < 8 || 4 * done < (reported + 1) * tiles) return;
         reported = 4 * done / tiles;
         Say(options, "N=%d: traced %d/%d tiles, %.1f Mrays", light_res, done, tiles, so_far / 1e6);
       }});
  if (!rays.ok()) {
    if (absl::IsCancelled(rays.status()))
      return absl::CancelledError("interrupted; nothing written");
    return rays.status();
  }
  ++report.traces;
  report.rays += *rays;
  Say(options, "N=%d: traced once, %.1f Mrays, %.1f s", light_res, *rays / 1e6, SecondsSince(t0));
  return absl::OkStatus();
}

// One candidate at (N, column target) coded from the trace into `store`,
// measured under every env.
struct Coded {
  AutoBakeMeasurement measurement;
  std::vector<double> all_lights, default_lights;  // per env
};

absl::StatusOr<Coded> CodeCandidate(Trace& trace, double column_target,
                                    const std::filesystem::path& store, const Measures& measures,
                                    const AutoBakeOptions& options) {
  const auto t0 = Clock::now();
  trace.ctx->params.target_error = column_target;
  if (absl::Status s = Recode(*trace.ctx, trace.dir, store, {.threads = Threads(options)}); !s.ok())
    return s;
  Coded c;
  AutoBakeMeasurement& m = c.measurement;
  const int all = trace.ctx->params.light_domain.Columns(trace.light_res);
  const int terms[] = {all, kDefaultRelightTerms};
  for (const auto& measure : measures) {
    absl::StatusOr<std::vector<double>> errors = measure->StoreErrors(store, terms, &m.bits);
    if (!errors.ok()) return errors.status();
    c.all_lights.push_back((*errors)[0]);
    c.default_lights.push_back((*errors)[1]);
  }
  m.e_tot = Worst(c.all_lights);
  m.e_tot_default = Worst(c.default_lights);
  m.bytes = DirectoryBytes(store);
  m.seconds = SecondsSince(t0);
  return c;
}

nlohmann::json ByEnv(const AutoBakeOptions& options, const std::vector<double>& v) {
  nlohmann::json j = nlohmann::json::object();
  for (size_t i = 0; i < v.size() && i < options.envs.size(); ++i) j[options.envs[i]] = v[i];
  return j;
}

nlohmann::json CandidateJson(const AutoCandidate& c, const AutoBakeReport& r, size_t row,
                             const AutoBakeOptions& options) {
  nlohmann::json j = {{"light_res", c.light_res}, {"e_disc", c.e_disc}, {"baked", c.baked}};
  if (row < r.e_disc_by_env.size()) j["e_disc_by_env"] = ByEnv(options, r.e_disc_by_env[row]);
  if (!c.baked) return j;
  j["column_target"] = c.column_target;
  j["bits"] = c.bake.bits;
  j["bytes"] = c.bake.bytes;
  j["e_tot"] = c.bake.e_tot;
  j["e_tot_default_terms"] = c.bake.e_tot_default;
  if (row < r.e_tot_by_env.size() && !r.e_tot_by_env[row].empty()) {
    j["e_tot_by_env"] = ByEnv(options, r.e_tot_by_env[row]);
    j["e_tot_default_terms_by_env"] = ByEnv(options, r.e_tot_default_by_env[row]);
  }
  j["seconds"] = c.bake.seconds;
  j["meets"] = c.meets;
  return j;
}

nlohmann::json AutoRecord(const AutoBakeReport& r, const AutoBakeOptions& options) {
  nlohmann::json j;
  j["target_error"] = options.search.target_error;
  j["envs"] = options.envs;
  j["env"] = options.envs.front();  // the first, as before several could be given
  j["metric"] =
      "rel_rms of the relit sample grid vs the independent reference, the worst of the envs";
  j["default_terms"] = kDefaultRelightTerms;
  j["reference"] = {{"rel_se", r.reference_rel_se}, {"seconds", r.reference_seconds}};
  j["traces"] = {{"light_resolutions", r.traces}, {"rays", r.rays}};
  j["candidates"] = nlohmann::json::array();
  const auto& candidates = r.search.candidates();
  for (size_t i = 0; i < candidates.size(); ++i)
    j["candidates"].push_back(CandidateJson(candidates[i], r, i, options));
  if (r.search.chosen()) {
    const size_t i = *r.search.chosen();
    j["chosen"] = CandidateJson(candidates[i], r, i, options);
    j["measured_error"] = candidates[i].bake.e_tot;
  }
  j["seconds"] = r.seconds;
  return j;
}

// The per-env rows follow the search's candidate rows: a row the search
// adds for a retry at the same N repeats that N's e_disc.
void SyncDiscRows(const AutoSearch& search, AutoBakeReport& report,
                  const std::vector<double>& e_disc) {
  while (report.e_disc_by_env.size() < search.candidates().size())
    report.e_disc_by_env.push_back(e_disc);
}

// The search loop proper: what Next() asks, measured, until done or failed.
absl::Status Search(const std::string& scene, const BakeParams& base, const Measures& measures,
                    const std::filesystem::path& dir, const AutoBakeOptions& options,
                    AutoBakeReport& report, std::filesystem::path* chosen_store) {
  AutoSearch& search = report.search;
  std::map<size_t, std::filesystem::path> stores;  // candidate row → its store, if it met E
  Trace trace;
  std::vector<double> e_disc;  // of the traced N, per env
  for (AutoAction a = search.Next(); a.step == AutoStep::kMeasureDisc || a.step == AutoStep::kBake;
       a = search.Next()) {
    if (options.interrupted && options.interrupted->load())
      return absl::CancelledError("interrupted; nothing written");
    if (a.step == AutoStep::kMeasureDisc) {
      // Each N is traced once: its e_disc and every candidate come from it.
      if (!trace.dir.empty()) std::filesystem::remove_all(trace.dir);
      if (absl::Status s = TraceResolution(scene, base, a.light_res, dir, options, report, trace);
          !s.ok())
        return s;
      e_disc.clear();
      for (const auto& measure : measures) {
        absl::StatusOr<double> e = measure->StagingError(*trace.ctx, trace.dir);
        if (!e.ok()) return e.status();
        e_disc.push_back(*e);
      }
      const double worst = Worst(e_disc);
      Say(options, "N=%d: dense T error %.4f%s", a.light_res, worst,
          measures.size() > 1 ? " (the worst env's)" : "");
      search.OnDisc(worst);
      SyncDiscRows(search, report, e_disc);
      continue;
    }
    Say(options, "N=%d: coding with column target %.4f", a.light_res, a.column_target);
    const std::filesystem::path store =
        dir / absl::StrCat("N", a.light_res, "-", a.column_target, ".wbk");
    absl::StatusOr<Coded> coded = CodeCandidate(trace, a.column_target, store, measures, options);
    if (!coded.ok()) return coded.status();
    const AutoBakeMeasurement* m = &coded->measurement;
    Say(options, "N=%d: %d bits, %lld bytes, error %.4f (all lights), %.4f (%d lights)",
        a.light_res, m->bits, static_cast<long long>(m->bytes), m->e_tot, m->e_tot_default,
        kDefaultRelightTerms);
    search.OnBaked(*m);
    SyncDiscRows(search, report, e_disc);
    const size_t row = search.candidates().size() - 1;
    report.e_tot_by_env.resize(row + 1);
    report.e_tot_default_by_env.resize(row + 1);
    report.e_tot_by_env[row] = coded->all_lights;
    report.e_tot_default_by_env[row] = coded->default_lights;
    // Disk holds at most the stores that met E at one N (two), and one trace.
    if (search.candidates().back().meets) {
      stores[search.candidates().size() - 1] = store;
    } else {
      std::filesystem::remove_all(store);
    }
  }
  if (!trace.dir.empty()) std::filesystem::remove_all(trace.dir);
  if (search.chosen()) *chosen_store = stores.at(*search.chosen());
  if (search.Next().step == AutoStep::kFailed) report.failure = search.Next().reason;
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<AutoBakeReport> AutoBake(const std::string& scene, const BakeParams& base,
                                        const std::filesystem::path& out,
                                        const AutoBakeOptions& options) {
  const auto t0 = Clock::now();
  if (options.envs.empty()) return absl::InvalidArgumentError("env: give at least one");
  // The search owns the light resolution and the coding: the uniform step of
  // --bits auto is what keeps its error budget, and only adaptive depths
  // make the column target mean the same at every N.
  if (base.bits != 0) return absl::InvalidArgumentError("bits: --auto needs --bits auto");
  if (base.column_mode != ColumnMode::kAdaptive)
    return absl::InvalidArgumentError("column_mode: --auto needs --column-mode adaptive");
  // Its yardstick is an environment, which a plane face does not span.
  if (base.light_domain.is_plane())
    return absl::InvalidArgumentError(
        "light_domain: --auto measures under an environment and "
        "needs the cube");
  if (absl::Status s = CheckOutputPath(out); !s.ok()) return s;
  absl::StatusOr<Measures> measures = MakeMeasures(scene, base, options);
  if (!measures.ok()) return measures.status();
  // The traces and candidates, beside the output so the chosen store moves by rename.
  absl::StatusOr<ScopedDir> dir = ScopedDir::CreateBeside(out, "auto");
  if (!dir.ok()) return dir.status();

  AutoBakeReport report;
  report.search = AutoSearch(options.search);
  report.envs = options.envs;
  for (const auto& m : *measures) {
    report.reference_rel_se = std::max(report.reference_rel_se, m->reference().rel_se);
    report.reference_seconds += m->reference().seconds;
  }
  std::filesystem::path chosen;
  if (absl::Status s = Search(scene, base, *measures, dir->path(), options, report, &chosen);
      !s.ok())
    return s;
  report.seconds = SecondsSince(t0);
  report.record = AutoRecord(report, options);
  if (!report.failure.empty()) return report;

  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(chosen);
  if (!attrs.ok()) return attrs.status();
  (*attrs)["auto"] = report.record;
  if (absl::Status s = WriteAttrs(chosen, *attrs); !s.ok()) return s;
  if (absl::Status s = PublishStore(chosen, out); !s.ok()) return s;
  return report;
}

std::string AutoBakeTable(const AutoBakeReport& report) {
  std::string text = absl::StrCat("   N  e_disc  col.target  bits       bytes   e_tot  e_tot@",
                                  kDefaultRelightTerms, "  seconds\n");
  char line[200];
  const auto& candidates = report.search.candidates();
  // With several envs, which one set each row's e_tot (or e_disc).
  auto worst_env = [&](size_t row) -> std::string {
    if (report.envs.size() < 2) return "";
    const std::vector<std::vector<double>>& by =
        candidates[row].baked ? report.e_tot_by_env : report.e_disc_by_env;
    if (row >= by.size() || by[row].empty()) return "";
    const size_t i = std::max_element(by[row].begin(), by[row].end()) - by[row].begin();
    return "  worst: " + EnvName(report.envs[i]);
  };
  for (size_t row = 0; row < candidates.size(); ++row) {
    const AutoCandidate& c = candidates[row];
    if (!c.baked) {
      std::snprintf(line, sizeof line, "%4d  %.4f  (no room for compression: not baked)%s\n",
                    c.light_res, c.e_disc, worst_env(row).c_str());
    } else {
      std::snprintf(line, sizeof line, "%4d  %.4f  %10.4f  %4d  %10lld  %.4f  %9.4f  %7.1f%s%s\n",
                    c.light_res, c.e_disc, c.column_target, c.bake.bits,
                    static_cast<long long>(c.bake.bytes), c.bake.e_tot, c.bake.e_tot_default,
                    c.bake.seconds, c.meets ? "  meets" : "", worst_env(row).c_str());
    }
    text += line;
  }
  std::snprintf(line, sizeof line, "%d light resolutions traced once each, %.1f Mrays\n",
                report.traces, report.rays / 1e6);
  text += line;
  std::snprintf(line, sizeof line, "reference rel SE %.5f (%.1f s); search %.1f s\n",
                report.reference_rel_se, report.reference_seconds, report.seconds);
  text += line;
  if (report.search.chosen()) {
    const AutoCandidate& c = report.search.candidates()[*report.search.chosen()];
    std::snprintf(line, sizeof line,
                  "chosen: N=%d, column target %.4f, %d bits, %lld bytes, error %.4f (target "
                  "%.4g)\n",
                  c.light_res, c.column_target, c.bake.bits, static_cast<long long>(c.bake.bytes),
                  c.bake.e_tot, report.search.config().target_error);
    text += line;
  }
  return text;
}

}  // namespace wavebake::driver
