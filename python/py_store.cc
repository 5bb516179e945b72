#include "python/py_store.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <mutex>
#include <optional>
#include <thread>

#include "absl/strings/str_cat.h"
#include "driver/bake/embedded_bake.h"
#include "proto/bake_request.h"
#include "python/py_convert.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/store/store_reader.h"

namespace wavebake::python {
namespace {

py::array_t<float> Vec3Array(const std::vector<Vec3>& v) {
  py::array_t<float> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto m = a.mutable_unchecked<2>();
  for (size_t i = 0; i < v.size(); ++i) {
    m(i, 0) = v[i].x, m(i, 1) = v[i].y, m(i, 2) = v[i].z;
  }
  return a;
}

py::dict Samples(const PyStore& s) {
  const SampleSet& set = s.samples();
  py::array_t<int32_t> grid({set.height, set.width});
  std::copy(set.grid.begin(), set.grid.end(), grid.mutable_data());
  py::dict out;
  out["grid"] = grid;
  out["position"] = Vec3Array(set.position);
  out["normal"] = Vec3Array(set.normal);
  out["albedo"] = Vec3Array(set.albedo);
  if (!set.vertex.empty()) {
    py::array_t<int32_t> vertex(static_cast<py::ssize_t>(set.vertex.size()));
    std::copy(set.vertex.begin(), set.vertex.end(), vertex.mutable_data());
    out["vertex"] = vertex;
  }
  return out;
}

// Column i of T: as stored (its depth, kept positions and values in the
// column's transform domain) or decoded to the W×H image of the grid.
py::object Column(PyStore& s, int column, const std::string& domain) {
  if (column < 0 || column >= s.info().columns) {
    throw py::index_error(absl::StrCat("column: ", column, " is not in 0..", s.info().columns - 1));
  }
  if (domain == "wavelet") {
    DecodedColumn c = Unwrap(ReadColumn(s.path(), column));
    py::array_t<uint32_t> positions(static_cast<py::ssize_t>(c.positions.size()));
    std::copy(c.positions.begin(), c.positions.end(), positions.mutable_data());
    py::array_t<float> values(static_cast<py::ssize_t>(c.values.size()));
    std::copy(c.values.begin(), c.values.end(), values.mutable_data());
    return py::make_tuple(c.depth, positions, values);
  }
  if (domain != "pixel") RaiseInvalid("domain: 'pixel' or 'wavelet'");
  auto [opened, lock] = s.Opened();
  // The column's inverse transform is Eq. 8 with the one light of weight 1.
  const WaveletLight light{static_cast<uint32_t>(column), {1, 1, 1}};
  std::vector<float> rgb(3 * static_cast<size_t>(opened->relighter.cells()));
  opened->relighter.RelightTransport({&light, 1}, rgb);
  py::array_t<float> image({s.info().height, s.info().width});
  float* out = image.mutable_data();
  for (size_t cell = 0; cell < rgb.size() / 3; ++cell) out[cell] = rgb[3 * cell];
  return image;
}

py::dict Bake(const std::string& scene, const std::string& out, int workers,
              const py::kwargs& params) {
  v1::BakeRequest request;
  SetRequestFields(request, params);
  // The scene goes to EmbeddedBake itself; checking the fields needs one.
  request.mutable_scene()->set_builtin("furnace");
  const BakeParams bake_params = Unwrap(ToBakeParams(request));
  absl::StatusOr<v1::Job> job;
  RunInterruptible([&](const std::atomic<bool>& interrupted) {
    job = driver::EmbeddedBake(scene, bake_params, out,
                               {.workers = workers, .interrupted = &interrupted});
  });
  return MessageToDict(Unwrap(std::move(job)));
}

}  // namespace

// Waits for the store with the GIL released: a thread holding the store may
// be waiting for the GIL.
std::unique_lock<std::mutex> PyStore::Lock() {
  std::unique_lock lock(mu_, std::defer_lock);
  py::gil_scoped_release release;
  lock.lock();
  return lock;
}

PyStore::PyStore(std::string path)
    : path_(std::move(path)),
      info_(Unwrap(ReadStoreInfo(path_))),
      samples_(Unwrap(ReadSamples(path_))) {}

std::pair<OpenedStore*, std::unique_lock<std::mutex>> PyStore::Opened() {
  std::unique_lock lock = Lock();
  if (!opened_) {
    absl::StatusOr<OpenedStore> s;
    {
      py::gil_scoped_release release;
      s = OpenStore(path_);
    }
    opened_.emplace(Unwrap(std::move(s)));
  }
  return {&*opened_, std::move(lock)};
}

std::pair<GlossyStore*, std::unique_lock<std::mutex>> PyStore::Glossy(
    const GlossyOptions& options) {
  std::unique_lock lock = Lock();
  absl::Status status;
  {
    py::gil_scoped_release release;
    if (!glossy_ || glossy_eye_.has_value() != options.eye.has_value() ||
        (options.eye && !(glossy_eye_->x == options.eye->x && glossy_eye_->y == options.eye->y &&
                          glossy_eye_->z == options.eye->z))) {
      absl::StatusOr<std::unique_ptr<GlossyStore>> g = GlossyStore::Open(path_, options);
      if (g.ok()) {
        glossy_ = *std::move(g);
        glossy_eye_ = options.eye;
        glossy_brdf_ = options.brdf;
      } else {
        status = g.status();
      }
    } else if (glossy_brdf_ != options.brdf) {
      status = glossy_->SetBrdf(options.brdf);
      if (status.ok()) glossy_brdf_ = options.brdf;
    }
  }
  Check(status);
  return {glossy_.get(), std::move(lock)};
}

std::pair<NearFieldStore*, std::unique_lock<std::mutex>> PyStore::NearField() {
  std::unique_lock lock = Lock();
  if (!near_) {
    absl::StatusOr<NearFieldStore> s;
    {
      py::gil_scoped_release release;
      s = OpenNearFieldStore(path_);
    }
    near_.emplace(Unwrap(std::move(s)));
  }
  return {&*near_, std::move(lock)};
}

PyStore& StoreOf(const py::object& store, std::optional<PyStore>& owned) {
  if (py::isinstance<PyStore>(store)) return store.cast<PyStore&>();
  owned.emplace(py::str(store).cast<std::string>());
  return *owned;
}

void RunInterruptible(const std::function<void(const std::atomic<bool>&)>& work) {
  std::atomic<bool> interrupted{false};
  std::future<void> done = std::async(std::launch::async, [&] { work(interrupted); });
  for (;;) {
    {
      py::gil_scoped_release release;
      if (done.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready) break;
    }
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      {
        py::gil_scoped_release release;
        done.wait();
      }
      throw py::error_already_set();
    }
  }
  done.get();
}

void AddStoreBindings(py::module_& m) {
  py::class_<PyStore>(m, "Store", "A finished wavebake store (a Zarr v2 directory).")
      .def(py::init<std::string>(), py::arg("path"))
      .def_property_readonly("path", &PyStore::path)
      .def_property_readonly(
          "attrs", [](const PyStore& s) { return JsonToPython(s.info().attrs); },
          "the root .zattrs: format, params, scene, statistics")
      .def_property_readonly(
          "params",
          [](const PyStore& s) {
            return JsonToPython(s.info().attrs.value("params", nlohmann::json::object()));
          })
      .def_property_readonly("width", [](const PyStore& s) { return s.info().width; })
      .def_property_readonly("height", [](const PyStore& s) { return s.info().height; })
      .def_property_readonly("light_res", [](const PyStore& s) { return s.info().light_res; })
      .def_property_readonly("columns", [](const PyStore& s) { return s.info().columns; })
      .def_property_readonly("layout", [](const PyStore& s) { return s.info().params.layout; })
      .def_property_readonly("samples", &Samples,
                             "dict of numpy arrays: grid (H, W), position, normal, albedo (S, 3), "
                             "vertex (S,) for mesh layouts")
      .def("column", &Column, py::arg("index"), py::arg("domain") = "pixel",
           "column `index` of T: a (H, W) image ('pixel'), or (depth, positions, values) "
           "as stored ('wavelet')")
      .def("__repr__", [](const PyStore& s) {
        return absl::StrCat("wavebake.Store('", s.path(), "', ", s.info().width, "x",
                            s.info().height, ", N=", s.info().light_res, ")");
      });
  m.def("bake", &Bake, py::arg("scene"), py::arg("out"), py::arg("workers") = 0,
        "bake SCENE into the store OUT in this process (as `wavebake bake`); keyword "
        "arguments are BakeRequest fields (light_res=16, layout='camera:32x32', ...)");
}

}  // namespace wavebake::python
