#pragma once
// wavebake.export: a diffuse store's rows as GPU wavelet-tree textures, as
// `wavebake export` writes them (driver/relight/tree_export.h).
#include <pybind11/pybind11.h>

namespace wavebake::python {

void AddExportBindings(pybind11::module_& m);

}  // namespace wavebake::python
