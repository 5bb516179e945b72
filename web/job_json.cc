#include "web/job_json.h"

#include <string>

#include "driver/job_text.h"

namespace wavebake::web {
namespace {

std::string SceneName(const v1::BakeRequest& r) {
  if (r.scene().has_builtin()) return r.scene().builtin();
  if (r.scene().has_uploaded()) return r.scene().uploaded().file_name();
  return "";
}

}  // namespace

nlohmann::json JobJson(const v1::Job& job) {
  const bool ended = job.phase() >= v1::PHASE_DONE;
  return {{"id", job.id()},
          {"phase", driver::PhaseName(job.phase())},
          {"scene", SceneName(job.request())},
          {"layout", job.request().layout()},
          {"light_res", job.request().light_res()},
          {"store_path", job.store_path()},
          {"tiles", job.tiles()},
          {"groups", job.groups()},
          {"tasks_done", job.tasks_done()},
          {"tasks_total", job.tasks_total()},
          {"leased_tasks", job.leased_tasks()},
          {"rays_traced", job.rays_traced()},
          {"rays_estimate", job.rays_estimate()},
          {"rays_per_second", job.rays_per_second()},
          {"bytes_written", job.bytes_written()},
          {"eta_seconds", job.eta_seconds() >= 0 ? nlohmann::json(job.eta_seconds()) : nullptr},
          {"error", job.error()},
          {"created_ms", job.created_ms()},
          {"started_ms", job.started_ms()},
          {"finished_ms", job.finished_ms()},
          {"ended", ended}};
}

nlohmann::json JobsJson(std::span<const v1::Job> jobs) {
  nlohmann::json out = nlohmann::json::array();
  for (const v1::Job& job : jobs) out.push_back(JobJson(job));
  return out;
}

nlohmann::json EventJson(const v1::JobEvent& e) {
  nlohmann::json j = {{"seq", e.seq()},
                      {"unix_ms", e.unix_ms()},
                      {"kind", v1::EventKind_Name(e.kind()).substr(6)},  // drop "EVENT_"
                      {"phase", driver::PhaseName(e.phase())},
                      {"worker", e.worker_id()},
                      {"message", e.message()},
                      {"tasks_done", e.tasks_done()},
                      {"tasks_total", e.tasks_total()}};
  if (e.task_kind() != v1::TASK_KIND_UNSPECIFIED) {
    j["task_kind"] = v1::TaskKind_Name(e.task_kind());
    j["task_index"] = e.task_index();
  }
  return j;
}

}  // namespace wavebake::web
