#include "driver/jobs/job_text.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "driver/jobs/job_json.h"

namespace wavebake::driver {

std::string PhaseName(v1::Phase phase) { return v1::Phase_Name(phase).substr(6); }

std::string PhaseLabel(v1::Phase phase) {
  switch (phase) {
    case v1::PHASE_BAKING:
      return "bake tiles";
    case v1::PHASE_TRANSFORMING:
      return "transform columns";
    case v1::PHASE_FINALIZING:
      return "finalize";
    default:
      return absl::AsciiStrToLower(PhaseName(phase));
  }
}

std::string JobDetailText(const v1::Job& job) {
  std::string text = absl::StrFormat(
      "job        %s\nphase      %s\nstore      %s\n"
      "tasks      %d/%d done (%d tiles, %d groups, 1 finalize), %d leased\n"
      "rays       %d of ~%d",
      job.id(), PhaseName(job.phase()), job.store_path(), job.tasks_done(), job.tasks_total(),
      job.tiles(), job.groups(), job.leased_tasks(), job.rays_traced(), job.rays_estimate());
  if (job.rays_per_second() > 0)
    absl::StrAppendFormat(&text, ", %.2f Mrays/s", job.rays_per_second() / 1e6);
  if (job.eta_seconds() >= 0) absl::StrAppendFormat(&text, ", ETA %.0f s", job.eta_seconds());
  absl::StrAppendFormat(&text, "\nwritten    %d bytes\n", job.bytes_written());
  if (!job.error().empty()) absl::StrAppend(&text, "error      ", job.error(), "\n");
  if (!job.stats_json().empty()) absl::StrAppend(&text, "stats      ", job.stats_json(), "\n");
  return text;
}

std::string ProgressText(const v1::JobEvent& e, double elapsed) {
  const int64_t done = e.phase_tasks_done(), total = e.phase_tasks_total();
  const double frac = total > 0 ? double(done) / double(total) : 0;
  const double mrays = e.rays_per_second() >= 0 ? e.rays_per_second() / 1e6
                       : elapsed > 0            ? e.rays_traced() / elapsed / 1e6
                                                : 0;
  // The whole job's ETA from measured task times (coordinator/scheduling/eta_model.h).
  const std::string eta =
      e.eta_seconds() >= 0 ? absl::StrCat(std::lround(e.eta_seconds()), "s") : "--";
  std::string bar(30, '.');
  std::fill_n(bar.begin(), static_cast<int>(frac * 30), '#');
  return absl::StrFormat("%-18s [%s] %3d%% %d/%d  %.1f Mrays/s  ETA %s", PhaseLabel(e.phase()), bar,
                         static_cast<int>(frac * 100), done, total, mrays, eta);
}

std::string JobTableHeader() {
  return absl::StrFormat("%-6s %-13s %9s %12s %-24s %s\n", "JOB", "PHASE", "TASKS", "RAYS", "STORE",
                         "ERROR");
}

std::string JobTableRow(const v1::Job& job) {
  return absl::StrFormat("%-6s %-13s %9s %12.4g %-24s %s\n", job.id(), PhaseName(job.phase()),
                         absl::StrCat(job.tasks_done(), "/", job.tasks_total()),
                         static_cast<double>(job.rays_traced()), job.store_path(), job.error());
}

std::string JobJson(const v1::Job& job) { return MessageJson(job).dump() + "\n"; }

}  // namespace wavebake::driver
