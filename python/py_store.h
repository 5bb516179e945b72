#pragma once
// wavebake.Store and the functions that read one (relight, eval) and make
// one (bake): the runtime and the embedded bake (driver/) seen from Python.
#include <pybind11/pybind11.h>

namespace wavebake::python {

void AddStoreBindings(pybind11::module_& m);

// Runs `work` on a thread of its own with the GIL released, checking for
// Ctrl-C every 100 ms; on one, raises `interrupted` and waits for the work
// to notice it (then rethrows KeyboardInterrupt).
void RunInterruptible(const std::function<void(const std::atomic<bool>& interrupted)>& work);

}  // namespace wavebake::python
