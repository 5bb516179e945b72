#pragma once
// wavebake.Client: a running coordinator's jobs from Python (DESIGN.md §4),
// on the driver's job client (driver/jobs/client.h, job_submit.h, job_watch.h,
// job_query.h, store_fetch.h).
#include <pybind11/pybind11.h>

namespace wavebake::python {

void AddClientBindings(pybind11::module_& m);

}  // namespace wavebake::python
