#pragma once
// wavebake.relight and wavebake.eval for every kind of store and light:
// environments on a diffuse store (Eq. 8) or through a BRDF on a visibility
// store (the triple product, runtime/glossy/glossy_store.h), and near-field area
// lights on a plane store (runtime/near_field/near_field.h); the same runtime calls
// `wavebake relight` and `wavebake eval` make, so the floats are the same.
#include <pybind11/pybind11.h>

namespace wavebake::python {

void AddShadingBindings(pybind11::module_& m);

}  // namespace wavebake::python
