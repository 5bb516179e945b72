#include "python/py_shading.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/products/brdf.h"
#include "driver/eval/evaluate.h"
#include "driver/relight/area_light_commands.h"
#include "driver/relight/area_relight.h"
#include "python/py_convert.h"
#include "python/py_store.h"
#include "runtime/env/env_map.h"
#include "runtime/glossy/glossy_store.h"
#include "runtime/near_field/area_light.h"
#include "runtime/near_field/near_field.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/finite_output.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"

namespace wavebake::python {
namespace {

// ENV: a LoadEnvMap spec, or a lat-long float array (H, 2H, 3) of radiance.
EnvMap EnvFrom(const py::object& env) {
  if (py::isinstance<py::str>(env)) return Unwrap(LoadEnvMap(env.cast<std::string>()));
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(env);
  if (!a || a.ndim() != 3 || a.shape(2) != 3 || a.shape(1) != 2 * a.shape(0) || a.shape(0) < 1) {
    RaiseInvalid("env: a spec string or a lat-long array of shape (H, 2H, 3)");
  }
  EnvMap map;
  map.width = static_cast<int>(a.shape(1));
  map.height = static_cast<int>(a.shape(0));
  map.rgb.assign(a.data(), a.data() + a.size());
  // The bound files get (kMaxEnvRadiance): a finite 3e38 relit to all NaN.
  if (absl::Status s = CheckEnvRadiance("env (array)", map); !s.ok())
    RaiseInvalid(std::string(s.message()));
  return map;
}

// An (H, W, 3) float32 array of the relit RGB, × 2^exposure (stops).
py::array_t<float> ToImage(const std::vector<float>& rgb, int width, int height, double exposure) {
  py::array_t<float> image({height, width, 3});
  float* out = image.mutable_data();
  std::copy(rgb.begin(), rgb.end(), out);
  if (exposure != 0) {
    const float scale = static_cast<float>(std::exp2(exposure));
    for (size_t i = 0; i < rgb.size(); ++i) {
      out[i] *= scale;
      // Masked cells stay NaN; a finite value times a finite scale is inf or finite.
      if (std::isinf(out[i]))
        RaiseInvalid(absl::StrCat("exposure: ", exposure, " stops overflow single precision at (",
                                  (i / 3) % width, ", ", i / 3 / width, "); lower it"));
    }
  }
  return image;
}

// view=(x, y, z): the eye of a mesh layout's glossy relighting, or None.
std::optional<Vec3> EyeFrom(const py::object& view) {
  if (view.is_none()) return std::nullopt;
  std::vector<double> v;
  try {
    v = view.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    RaiseInvalid("view: an eye position (x, y, z), or None");
  }
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    RaiseInvalid("view: an eye position of three finite numbers (x, y, z)");
  return Vec3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

void CheckFinite(double value, const char* name, const char* what) {
  if (!std::isfinite(value)) RaiseInvalid(absl::StrCat(name, ": ", value, " is not ", what));
}

// What each relighting and evaluation takes besides the store.
struct Shading {
  std::string brdf;
  std::optional<Vec3> eye;
  std::vector<std::filesystem::path> area_lights;
  double source_fraction = 0.01, target_fraction = 0.30;
};

Shading ShadingFrom(const std::string& brdf, const py::object& view,
                    const std::vector<std::string>& area_lights, double source_fraction,
                    double target_fraction) {
  Shading s{brdf, EyeFrom(view), {}, source_fraction, target_fraction};
  for (const std::string& f : area_lights) s.area_lights.emplace_back(f);
  return s;
}

// A diffuse store takes the Lambertian BRDF and no view (as the command
// line's RelightStoreToFile says).
void CheckDiffuseShading(const PyStore& s, const Shading& shading) {
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(shading.brdf);
  if (!brdf.ok()) Raise(brdf.status());
  if ((*brdf)->Name() != "lambert") Check(CheckVisibilityStore(s.info()));
  if (shading.eye)
    RaiseInvalid(
        "view: a diffuse store is relit the same from every view; a view needs a visibility "
        "store and a glossy brdf");
}

bool IsVisibility(const PyStore& s) { return s.info().params.transport == Transport::kVisibility; }

// Near-field: every light of every file (they add) through the plane store.
std::vector<float> RelightArea(PyStore& s, const Shading& shading,
                               const std::optional<AreaLight>& moving) {
  auto held = s.NearField();
  const NearFieldStore* near = held.first;
  absl::StatusOr<std::vector<float>> rgb;
  {
    py::gil_scoped_release release;
    rgb = [&]() -> absl::StatusOr<std::vector<float>> {
      absl::StatusOr<std::vector<AreaLight>> lights =
          driver::LoadAllAreaLights(shading.area_lights);
      if (!lights.ok()) return lights.status();
      if (moving) lights->push_back(*moving);
      if (lights->empty()) return absl::InvalidArgumentError("area_lights: no light given");
      std::vector<float> out(3 * static_cast<size_t>(near->samples.cells()));
      absl::StatusOr<NearFieldStats> stats = RelightNearField(
          *near, *lights,
          {.source_fraction = shading.source_fraction, .target_fraction = shading.target_fraction},
          out);
      if (!stats.ok()) return stats.status();
      return out;
    }();
  }
  return Unwrap(std::move(rgb));
}

py::array_t<float> Relight(const py::object& store, const py::object& env, int terms, double rotate,
                           const std::string& brdf, const py::object& view, double exposure,
                           const std::vector<std::string>& area_lights, double source_fraction,
                           double target_fraction) {
  std::optional<PyStore> owned;
  PyStore& s = StoreOf(store, owned);
  CheckFinite(rotate, "rotate", "a finite number of degrees");
  Check(CheckExposure(exposure));
  const Shading shading = ShadingFrom(brdf, view, area_lights, source_fraction, target_fraction);
  const int width = s.info().width, height = s.info().height;
  if (!shading.area_lights.empty()) {
    if (!env.is_none()) RaiseInvalid("env: area_lights light the store by themselves; env=None");
    return ToImage(RelightArea(s, shading, std::nullopt), width, height, exposure);
  }
  if (env.is_none()) RaiseInvalid("env: give an environment (or area_lights)");
  if (terms <= 0) RaiseInvalid(absl::StrCat("terms: ", terms, "; need at least 1"));
  EnvMap map = EnvFrom(env);
  absl::StatusOr<std::vector<float>> rgb;
  if (IsVisibility(s)) {
    GlossyOptions options;
    options.brdf = shading.brdf;
    options.eye = shading.eye;
    auto [glossy, lock] = s.Glossy(options);
    py::gil_scoped_release release;
    if (rotate != 0) map = Rotated(map, rotate);
    rgb = glossy->RelightImage(map, terms);
  } else {
    CheckDiffuseShading(s, shading);
    auto [opened, lock] = s.Opened();
    py::gil_scoped_release release;
    if (rotate != 0) map = Rotated(map, rotate);
    rgb = RelightImage(*opened, map, terms);
  }
  return ToImage(Unwrap(std::move(rgb)), width, height, exposure);
}

// Frame `frame` of an area-light sequence (SEQ.json; runtime/near_field/area_light.h)
// over the fixed area_lights, as `relight --area-light-sequence` renders it.
py::array_t<float> RelightAreaFrame(const py::object& store, const std::string& sequence, int frame,
                                    const std::vector<std::string>& area_lights, double exposure,
                                    double source_fraction, double target_fraction) {
  std::optional<PyStore> owned;
  PyStore& s = StoreOf(store, owned);
  Check(CheckExposure(exposure));
  const AreaLightSequence seq = Unwrap(LoadAreaLightSequence(sequence));
  if (frame < 0 || frame >= seq.frames)
    throw py::index_error(absl::StrCat("frame: ", frame, " is not in 0..", seq.frames - 1));
  const Shading shading =
      ShadingFrom("lambert", py::none(), area_lights, source_fraction, target_fraction);
  return ToImage(RelightArea(s, shading, seq.Frame(frame)), s.info().width, s.info().height,
                 exposure);
}

int AreaSequenceFrames(const std::string& sequence) {
  return Unwrap(LoadAreaLightSequence(sequence)).frames;
}

// reference=False: the n-term relighting against all wavelet lights (what
// the lighting approximation alone costs), no tracing.
py::dict EvalAgainstAllLights(PyStore& s, const py::object& env, int terms, double rotate,
                              const Shading& shading) {
  EnvMap map = EnvFrom(env);
  struct Result {
    int terms = 0;
    double seconds = 0;
    ErrorStats error;
  };
  absl::StatusOr<Result> result;
  const auto timed = [&](auto relight_n, auto relight_all, int used) -> absl::StatusOr<Result> {
    const auto start = std::chrono::steady_clock::now();
    absl::StatusOr<std::vector<float>> image = relight_n();
    if (!image.ok()) return image.status();
    Result res;
    res.terms = used;
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    absl::StatusOr<std::vector<float>> all = relight_all();
    if (!all.ok()) return all.status();
    // Masked cells are NaN in both; any other NaN or inf is an overflow to
    // report, not a perfect score.
    absl::StatusOr<ErrorStats> error = CompareFinite(*image, *all, "the n-term relighting");
    if (!error.ok()) return error.status();
    res.error = *error;
    return res;
  };
  if (IsVisibility(s)) {
    GlossyOptions options;
    options.brdf = shading.brdf;
    options.eye = shading.eye;
    auto held = s.Glossy(options);
    GlossyStore* glossy = held.first;
    const int columns = s.info().columns;
    py::gil_scoped_release release;
    if (rotate != 0) map = Rotated(map, rotate);
    result = timed([&] { return glossy->RelightImage(map, terms); },
                   [&] { return glossy->RelightImage(map, columns); }, std::min(terms, columns));
  } else {
    CheckDiffuseShading(s, shading);
    auto held = s.Opened();
    Relighter& r = held.first->relighter;
    py::gil_scoped_release release;
    result = [&]() -> absl::StatusOr<Result> {
      if (rotate != 0) map = Rotated(map, rotate);
      absl::StatusOr<LightingCoefficients> lighting =
          LightingFromEnv(map, r.light_res(), r.row_filter());
      if (!lighting.ok()) return lighting.status();
      absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, terms);
      if (!lights.ok()) return lights.status();
      std::vector<float> image(3 * static_cast<size_t>(r.cells()));
      return timed(
          [&]() -> absl::StatusOr<std::vector<float>> {
            r.Relight(*lights, image);
            return image;
          },
          [&]() -> absl::StatusOr<std::vector<float>> {
            std::vector<float> all(image.size());
            r.Relight(AllWaveletLights(*lighting), all);
            return all;
          },
          static_cast<int>(lights->lights.size()));
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

// reference=True: runtime/reference/eval.h (or runtime/reference/area_eval.h for area lights)
// against the independent Monte-Carlo reference, as `wavebake eval --json`.
py::object Eval(const py::object& store, const py::object& env, bool reference, int terms,
                double rotate, bool dense, double target_rel_se, const std::string& brdf,
                const py::object& view, const std::vector<std::string>& area_lights,
                double source_fraction, double target_fraction, int reference_batches) {
  std::optional<PyStore> owned;
  PyStore& s = StoreOf(store, owned);
  CheckFinite(rotate, "rotate", "a finite number of degrees");
  const Shading shading = ShadingFrom(brdf, view, area_lights, source_fraction, target_fraction);
  if (!shading.area_lights.empty()) {
    if (!env.is_none()) RaiseInvalid("env: area_lights light the store by themselves; env=None");
    if (!reference) RaiseInvalid("reference: area lights are measured against the reference");
    driver::AreaLightCommand command;
    command.store = s.path();
    command.lights = area_lights;
    command.source_fraction = source_fraction;
    command.target_fraction = target_fraction;
    absl::StatusOr<std::string> json;
    {
      py::gil_scoped_release release;
      json = driver::EvaluateWithAreaLights(command, reference_batches, /*json=*/true);
    }
    return JsonToPython(nlohmann::json::parse(Unwrap(std::move(json))));
  }
  if (env.is_none()) RaiseInvalid("env: give an environment (or area_lights)");
  if (!reference) return EvalAgainstAllLights(s, env, terms, rotate, shading);
  if (!py::isinstance<py::str>(env))
    throw py::type_error("env: eval(reference=True) takes a spec string");
  EvalOptions options;
  options.rotate_degrees = rotate;
  options.dense = dense;
  options.reference.target_rel_se = target_rel_se;
  options.glossy.brdf = shading.brdf;
  options.glossy.eye = shading.eye;
  const std::string spec = env.cast<std::string>();
  absl::StatusOr<EvalReport> report;
  {
    py::gil_scoped_release release;
    report = driver::Evaluate(s.path(), spec, terms, options);
  }
  return JsonToPython(EvalReportJson(Unwrap(std::move(report))));
}

}  // namespace

void AddShadingBindings(py::module_& m) {
  m.def("relight", &Relight, py::arg("store"), py::arg("env"), py::arg("terms"), py::arg("rotate"),
        py::arg("brdf"), py::arg("view"), py::arg("exposure"), py::arg("area_lights"),
        py::arg("source_fraction"), py::arg("target_fraction"),
        "the store relit: an (H, W, 3) float32 array, NaN where masked (wavebake.relight)");
  m.def("relight_area_frame", &RelightAreaFrame, py::arg("store"), py::arg("sequence"),
        py::arg("frame"), py::arg("area_lights"), py::arg("exposure"), py::arg("source_fraction"),
        py::arg("target_fraction"),
        "frame `frame` of an area-light sequence (wavebake.relight_sequence)");
  m.def("area_sequence_frames", &AreaSequenceFrames, py::arg("sequence"),
        "the number of frames of an area-light sequence file");
  m.def("eval", &Eval, py::arg("store"), py::arg("env"), py::arg("reference"), py::arg("terms"),
        py::arg("rotate"), py::arg("dense"), py::arg("target_rel_se"), py::arg("brdf"),
        py::arg("view"), py::arg("area_lights"), py::arg("source_fraction"),
        py::arg("target_fraction"), py::arg("reference_batches"),
        "relighting error as a dict (wavebake.eval)");
}

}  // namespace wavebake::python
