// `import wavebake` (DESIGN.md §6 python/): stores, relighting and
// evaluation (runtime/), the GPU export, the embedded bake and the job
// client (driver/).
#include <pybind11/pybind11.h>
#include <spdlog/spdlog.h>

#include "python/py_client.h"
#include "python/py_export.h"
#include "python/py_shading.h"
#include "python/py_store.h"

PYBIND11_MODULE(_wavebake, m) {
  m.doc() = "wavebake: bake, read and relight compressed all-frequency light transport";
  m.attr("__version__") = WB_VERSION;
  // The embedded bake's per-task lines are for the command line's log, not
  // a notebook's output; warnings and errors still show.
  spdlog::set_level(spdlog::level::warn);
  wavebake::python::AddStoreBindings(m);
  wavebake::python::AddShadingBindings(m);
  wavebake::python::AddClientBindings(m);
  wavebake::python::AddExportBindings(m);
}
