#pragma once
// wavebake.Store and the functions that read one (relight, eval) and make
// one (bake): the runtime and the embedded bake (driver/) seen from Python.
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "runtime/glossy/glossy_store.h"
#include "runtime/near_field/near_field.h"
#include "runtime/relight/store_relight.h"
#include "storage/store/store_reader.h"

namespace wavebake::python {

// A finished store (DESIGN.md §3): its metadata and samples at once; what
// relighting needs (the transport matrix, a visibility store's rows and BRDF
// slices, a plane store's rows) opened on first use and kept for later calls.
// Each getter returns its state with the store's lock held: one frame at a
// time. Call them with the GIL held; they release it while they read.
class PyStore {
 public:
  explicit PyStore(std::string path);

  const std::string& path() const { return path_; }
  const StoreInfo& info() const { return info_; }
  const SampleSet& samples() const { return samples_; }

  std::pair<OpenedStore*, std::unique_lock<std::mutex>> Opened();
  // Reopened when the view changes; the BRDF is swapped in place (SetBrdf).
  std::pair<GlossyStore*, std::unique_lock<std::mutex>> Glossy(const GlossyOptions& options);
  std::pair<NearFieldStore*, std::unique_lock<std::mutex>> NearField();

 private:
  std::unique_lock<std::mutex> Lock();

  std::string path_;
  StoreInfo info_;
  SampleSet samples_;
  std::mutex mu_;
  std::optional<OpenedStore> opened_;
  std::unique_ptr<GlossyStore> glossy_;
  std::optional<Vec3> glossy_eye_;
  std::string glossy_brdf_;
  std::optional<NearFieldStore> near_;
};

// A Store, or a path (str) opened for this call into `owned`.
PyStore& StoreOf(const pybind11::object& store, std::optional<PyStore>& owned);

void AddStoreBindings(pybind11::module_& m);

// Runs `work` on a thread of its own with the GIL released, checking for
// Ctrl-C every 100 ms; on one, raises `interrupted` and waits for the work
// to notice it (then rethrows KeyboardInterrupt).
void RunInterruptible(const std::function<void(const std::atomic<bool>& interrupted)>& work);

}  // namespace wavebake::python
