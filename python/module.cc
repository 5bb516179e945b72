// `import wavebake` (DESIGN.md §6 python/): stores, relighting and
// evaluation (runtime/), the embedded bake and the job client (driver/).
#include <pybind11/pybind11.h>

#include "python/py_client.h"
#include "python/py_store.h"

PYBIND11_MODULE(_wavebake, m) {
  m.doc() = "wavebake: bake, read and relight compressed all-frequency light transport";
  wavebake::python::AddStoreBindings(m);
  wavebake::python::AddClientBindings(m);
}
