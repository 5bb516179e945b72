#include "driver/auto_bake.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <memory>

#include "absl/strings/str_cat.h"
#include "driver/embedded_bake.h"
#include "driver/job_query.h"
#include "driver/reference_measure.h"
#include "storage/scoped_dir.h"
#include "storage/zarr_group.h"
#include "worker/publish_store.h"

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

absl::StatusOr<std::unique_ptr<ReferenceMeasure>> MakeMeasure(const std::string& scene,
                                                              const BakeParams& base,
                                                              const AutoBakeOptions& options) {
  // The reference's own error inflates every measured e_tot (e² + SE²):
  // keeping it below E/5 bounds that to 2 % of E; it is not subtracted, so
  // the measurements err on the safe side.
  const double target_se = std::min(0.002, options.search.target_error / 5);
  Say(options, "tracing the reference under %s (target rel SE %.4f)", options.env.c_str(),
      target_se);
  absl::StatusOr<std::unique_ptr<ReferenceMeasure>> measure =
      ReferenceMeasure::Create(scene, base, options.env, target_se);
  if (!measure.ok()) return measure.status();
  const ReferenceResult& r = (*measure)->reference();
  Say(options, "reference: %d samples, rel SE %.5f, %.1f Mrays, %.1f s", (*measure)->samples(),
      r.rel_se, r.rays / 1e6, r.seconds);
  return measure;
}

// One candidate bake at (N, column target) into `dir`, measured.
absl::StatusOr<AutoBakeMeasurement> BakeCandidate(const std::string& scene, BakeParams params,
                                                  const AutoAction& action,
                                                  const std::filesystem::path& store,
                                                  const ReferenceMeasure& measurer,
                                                  const AutoBakeOptions& options) {
  const auto t0 = Clock::now();
  params.light_res = action.light_res;
  params.target_error = action.column_target;
  absl::StatusOr<v1::Job> job = EmbeddedBake(scene, params, store,
                                             {.workers = options.workers,
                                              .on_event = options.on_event,
                                              .interrupted = options.interrupted});
  if (!job.ok()) return job.status();
  if (options.interrupted && options.interrupted->load())
    return absl::CancelledError("interrupted; nothing written");
  if (job->phase() != v1::PHASE_DONE) return absl::InternalError(JobOutcome(*job));
  AutoBakeMeasurement m;
  const int all = params.light_domain.Columns(action.light_res);
  const int terms[] = {all, kDefaultRelightTerms};
  absl::StatusOr<std::vector<double>> errors = measurer.StoreErrors(store, terms, &m.bits);
  if (!errors.ok()) return errors.status();
  m.e_tot = (*errors)[0];
  m.e_tot_default = (*errors)[1];
  m.bytes = DirectoryBytes(store);
  m.seconds = SecondsSince(t0);
  return m;
}

nlohmann::json CandidateJson(const AutoCandidate& c) {
  nlohmann::json j = {{"light_res", c.light_res}, {"e_disc", c.e_disc}, {"baked", c.baked}};
  if (!c.baked) return j;
  j["column_target"] = c.column_target;
  j["bits"] = c.bake.bits;
  j["bytes"] = c.bake.bytes;
  j["e_tot"] = c.bake.e_tot;
  j["e_tot_default_terms"] = c.bake.e_tot_default;
  j["seconds"] = c.bake.seconds;
  j["meets"] = c.meets;
  return j;
}

nlohmann::json AutoRecord(const AutoBakeReport& r, const AutoBakeOptions& options) {
  nlohmann::json j;
  j["target_error"] = options.search.target_error;
  j["env"] = options.env;
  j["metric"] = "rel_rms of the relit sample grid vs the independent reference";
  j["default_terms"] = kDefaultRelightTerms;
  j["reference"] = {{"rel_se", r.reference_rel_se}, {"seconds", r.reference_seconds}};
  j["candidates"] = nlohmann::json::array();
  for (const AutoCandidate& c : r.search.candidates()) j["candidates"].push_back(CandidateJson(c));
  if (r.search.chosen()) {
    const AutoCandidate& c = r.search.candidates()[*r.search.chosen()];
    j["chosen"] = CandidateJson(c);
    j["measured_error"] = c.bake.e_tot;
  }
  j["seconds"] = r.seconds;
  return j;
}

// The search loop proper: what Next() asks, measured, until done or failed.
absl::Status Search(const std::string& scene, const BakeParams& base,
                    const ReferenceMeasure& measurer, const std::filesystem::path& dir,
                    const AutoBakeOptions& options, AutoBakeReport& report,
                    std::filesystem::path* chosen_store) {
  AutoSearch& search = report.search;
  std::map<size_t, std::filesystem::path> stores;  // candidate row → its store, if it met E
  for (AutoAction a = search.Next(); a.step == AutoStep::kMeasureDisc || a.step == AutoStep::kBake;
       a = search.Next()) {
    if (options.interrupted && options.interrupted->load())
      return absl::CancelledError("interrupted; nothing written");
    if (a.step == AutoStep::kMeasureDisc) {
      const auto t0 = Clock::now();
      absl::StatusOr<double> e_disc = measurer.DenseError(a.light_res);
      if (!e_disc.ok()) return e_disc.status();
      Say(options, "N=%d: dense T error %.4f (%.1f s)", a.light_res, *e_disc, SecondsSince(t0));
      search.OnDisc(*e_disc);
      continue;
    }
    Say(options, "N=%d: baking with column target %.4f", a.light_res, a.column_target);
    const std::filesystem::path store =
        dir / absl::StrCat("N", a.light_res, "-", a.column_target, ".wbk");
    absl::StatusOr<AutoBakeMeasurement> m = BakeCandidate(scene, base, a, store, measurer, options);
    if (!m.ok()) return m.status();
    Say(options, "N=%d: %d bits, %lld bytes, error %.4f (all lights), %.4f (%d lights)",
        a.light_res, m->bits, static_cast<long long>(m->bytes), m->e_tot, m->e_tot_default,
        kDefaultRelightTerms);
    search.OnBaked(*m);
    // Disk holds at most the stores that met E at one N (two).
    if (search.candidates().back().meets) {
      stores[search.candidates().size() - 1] = store;
    } else {
      std::filesystem::remove_all(store);
    }
  }
  if (search.chosen()) *chosen_store = stores.at(*search.chosen());
  if (search.Next().step == AutoStep::kFailed) report.failure = search.Next().reason;
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<AutoBakeReport> AutoBake(const std::string& scene, const BakeParams& base,
                                        const std::filesystem::path& out,
                                        const AutoBakeOptions& options) {
  const auto t0 = Clock::now();
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
  absl::StatusOr<std::unique_ptr<ReferenceMeasure>> measurer = MakeMeasure(scene, base, options);
  if (!measurer.ok()) return measurer.status();
  // The candidates, beside the output so the chosen store moves by rename.
  absl::StatusOr<ScopedDir> dir = ScopedDir::CreateBeside(out, "auto");
  if (!dir.ok()) return dir.status();

  AutoBakeReport report;
  report.search = AutoSearch(options.search);
  report.reference_rel_se = (*measurer)->reference().rel_se;
  report.reference_seconds = (*measurer)->reference().seconds;
  std::filesystem::path chosen;
  if (absl::Status s = Search(scene, base, **measurer, dir->path(), options, report, &chosen);
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
  char line[160];
  for (const AutoCandidate& c : report.search.candidates()) {
    if (!c.baked) {
      std::snprintf(line, sizeof line, "%4d  %.4f  (no room for compression: not baked)\n",
                    c.light_res, c.e_disc);
    } else {
      std::snprintf(line, sizeof line, "%4d  %.4f  %10.4f  %4d  %10lld  %.4f  %9.4f  %7.1f%s\n",
                    c.light_res, c.e_disc, c.column_target, c.bake.bits,
                    static_cast<long long>(c.bake.bytes), c.bake.e_tot, c.bake.e_tot_default,
                    c.bake.seconds, c.meets ? "  meets" : "");
    }
    text += line;
  }
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
