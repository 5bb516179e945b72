#pragma once
// How a job reads to a person or a script (DESIGN.md §4 Job): the views that
// `wavebake status` prints and that the web monitor and Python module can show.
#include <string>

#include "wavebake.pb.h"

namespace wavebake::driver {

// "BAKING", "DONE", ... (the enum name without its PHASE_ prefix).
std::string PhaseName(v1::Phase phase);
// What a person calls the phase: "bake tiles", "transform columns", "finalize", "done" ...
std::string PhaseLabel(v1::Phase phase);

// One field per line: phase, store, tasks, rays (with rate and ETA when the
// coordinator knows them), bytes written, error and stats when present.
std::string JobDetailText(const v1::Job& job);

// One line of a job's progress in its phase: label, a bar of its tasks,
// done/total, rays/s (the coordinator's rate, else rays over `elapsed`
// seconds) and the coordinator's ETA ("--" until it has one).
std::string ProgressText(const v1::JobEvent& event, double elapsed_seconds);

// A table of jobs: the header, then one row per job (each ends in a newline).
std::string JobTableHeader();
std::string JobTableRow(const v1::Job& job);

// The Job message as one line of JSON (MessageJson: the one shape of a job,
// driver/jobs/job_json.h), and its newline.
std::string JobJson(const v1::Job& job);

}  // namespace wavebake::driver
