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
#include "driver/embedded_bake.h"
#include "proto/bake_request.h"
#include "python/py_convert.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/store_reader.h"

namespace wavebake::python {
namespace {

// A finished store (DESIGN.md §3): its metadata and samples at once, the
// transport matrix on first use (relight, column), kept for later calls.
class PyStore {
 public:
  explicit PyStore(std::string path)
      : path_(std::move(path)),
        info_(Unwrap(ReadStoreInfo(path_))),
        samples_(Unwrap(ReadSamples(path_))) {}

  const std::string& path() const { return path_; }
  const StoreInfo& info() const { return info_; }
  const SampleSet& samples() const { return samples_; }

  // The opened store with its lock: a Relighter serves one frame at a time.
  std::pair<OpenedStore*, std::unique_lock<std::mutex>> Opened() {
    std::unique_lock lock(mu_);
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

 private:
  std::string path_;
  StoreInfo info_;
  SampleSet samples_;
  std::mutex mu_;
  std::optional<OpenedStore> opened_;
};

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
  if (domain != "pixel") throw py::value_error("domain: 'pixel' or 'wavelet'");
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

// ENV: a LoadEnvMap spec, or a lat-long float array (H, 2H, 3) of radiance.
EnvMap EnvFrom(const py::object& env) {
  if (py::isinstance<py::str>(env)) return Unwrap(LoadEnvMap(env.cast<std::string>()));
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(env);
  if (!a || a.ndim() != 3 || a.shape(2) != 3 || a.shape(1) != 2 * a.shape(0) || a.shape(0) < 1) {
    throw py::value_error("env: a spec string or a lat-long array of shape (H, 2H, 3)");
  }
  EnvMap map;
  map.width = static_cast<int>(a.shape(1));
  map.height = static_cast<int>(a.shape(0));
  map.rgb.assign(a.data(), a.data() + a.size());
  for (size_t i = 0; i < map.rgb.size(); ++i) {
    if (!(std::isfinite(map.rgb[i]) && map.rgb[i] >= 0)) {
      throw py::value_error(absl::StrCat("env: value ", map.rgb[i], " at flat index ", i,
                                         " is not a finite non-negative radiance"));
    }
  }
  return map;
}

PyStore& StoreOf(const py::object& store, std::optional<PyStore>& owned) {
  if (py::isinstance<PyStore>(store)) return store.cast<PyStore&>();
  owned.emplace(py::str(store).cast<std::string>());
  return *owned;
}

py::array_t<float> ToImage(const std::vector<float>& rgb, int width, int height) {
  py::array_t<float> image({height, width, 3});
  std::copy(rgb.begin(), rgb.end(), image.mutable_data());
  return image;
}

py::array_t<float> Relight(const py::object& store, const py::object& env, int terms,
                           double rotate) {
  std::optional<PyStore> owned;
  PyStore& s = StoreOf(store, owned);
  EnvMap map = EnvFrom(env);
  if (!std::isfinite(rotate)) throw py::value_error("rotate: not a finite number of degrees");
  auto [opened, lock] = s.Opened();
  absl::StatusOr<std::vector<float>> rgb;
  {
    py::gil_scoped_release release;
    if (rotate != 0) map = Rotated(map, rotate);
    rgb = RelightImage(*opened, map, terms);
  }
  return ToImage(Unwrap(std::move(rgb)), s.info().width, s.info().height);
}

// reference=True: runtime/reference/eval.h against the independent Monte-Carlo
// reference. reference=False: the n-term relighting against all wavelet
// lights (what the lighting approximation alone costs), no tracing.
py::object Eval(const py::object& store, const py::object& env, bool reference, int terms,
                double rotate, bool dense, double target_rel_se) {
  std::optional<PyStore> owned;
  PyStore& s = StoreOf(store, owned);
  if (reference) {
    if (!py::isinstance<py::str>(env))
      throw py::type_error("env: eval(reference=True) takes a spec string");
    EvalOptions options;
    options.rotate_degrees = rotate;
    options.dense = dense;
    options.reference.target_rel_se = target_rel_se;
    const std::string spec = env.cast<std::string>();
    absl::StatusOr<EvalReport> report;
    {
      py::gil_scoped_release release;
      report = Evaluate(s.path(), spec, terms, options);
    }
    return JsonToPython(EvalReportJson(Unwrap(std::move(report))));
  }
  EnvMap map = EnvFrom(env);
  auto [opened, lock] = s.Opened();
  struct Result {
    int terms = 0;
    double seconds = 0;
    ErrorStats error;
  };
  absl::StatusOr<Result> result;
  {
    py::gil_scoped_release release;
    result = [&]() -> absl::StatusOr<Result> {
      if (rotate != 0) map = Rotated(map, rotate);
      Relighter& r = opened->relighter;
      const auto start = std::chrono::steady_clock::now();
      absl::StatusOr<LightingCoefficients> lighting =
          LightingFromEnv(map, r.light_res(), r.row_filter());
      if (!lighting.ok()) return lighting.status();
      absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, terms);
      if (!lights.ok()) return lights.status();
      std::vector<float> image(3 * static_cast<size_t>(r.cells())), all(image.size());
      r.Relight(*lights, image);
      Result res;
      res.terms = static_cast<int>(lights->lights.size());
      res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      r.Relight(AllWaveletLights(*lighting), all);
      res.error = CompareToReference(image, all);
      return res;
    }();
  }
  const Result r = Unwrap(std::move(result));
  py::dict out;
  out["terms"] = r.terms;
  out["vs_all_lights"] =
      py::dict(py::arg("rel_rms") = r.error.rel_rms, py::arg("max_abs") = r.error.max_abs,
               py::arg("psnr") = r.error.psnr, py::arg("seconds") = r.seconds);
  return out;
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
  m.def("relight", &Relight, py::arg("store"), py::arg("env"), py::arg("terms") = 256,
        py::arg("rotate") = 0.0,
        "the store relit by `terms` wavelet lights of env (a spec or an (H, 2H, 3) array) "
        "turned `rotate` degrees about +Y: an (H, W, 3) float32 array, NaN where masked");
  m.def("eval", &Eval, py::arg("store"), py::arg("env"), py::arg("reference") = true,
        py::arg("terms") = 256, py::arg("rotate") = 0.0, py::arg("dense") = true,
        py::arg("target_rel_se") = 0.002,
        "relighting error: against the independent reference (reference=True, as `wavebake "
        "eval --json`), or against all wavelet lights (reference=False)");
  m.def("bake", &Bake, py::arg("scene"), py::arg("out"), py::arg("workers") = 0,
        "bake SCENE into the store OUT in this process (as `wavebake bake`); keyword "
        "arguments are BakeRequest fields (light_res=16, layout='camera:32x32', ...)");
}

}  // namespace wavebake::python
