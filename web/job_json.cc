#include "web/job_json.h"

#include "driver/jobs/job_json.h"
#include "driver/jobs/job_text.h"

namespace wavebake::web {

nlohmann::json JobJson(const v1::Job& job) { return driver::MessageJson(job); }

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
