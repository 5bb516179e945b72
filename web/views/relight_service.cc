#include "web/views/relight_service.h"

#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "absl/strings/str_cat.h"
#include "runtime/env/env_map.h"
#include "runtime/io/tonemap.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/row_basis.h"

namespace wavebake::web {
namespace {

absl::Status CheckRequest(const RelightRequest& r) {
  if (r.terms < 1) return absl::InvalidArgumentError(absl::StrCat("terms: ", r.terms, " < 1"));
  if (!std::isfinite(r.rotate_degrees))
    return absl::InvalidArgumentError("rotate: not a finite number of degrees");
  if (!(std::abs(r.exposure_stops) <= 20))
    return absl::InvalidArgumentError(
        absl::StrCat("exposure: ", r.exposure_stops, " is not within -20..20 stops"));
  return absl::OkStatus();
}

// Masked or empty pixels: a dark grey that no relit surface is mistaken for.
constexpr Vec3 kBackground{0.02f, 0.02f, 0.025f};

void ToRgba(std::span<const float> rgb, double exposure_stops, std::vector<uint8_t>& rgba) {
  const float scale = static_cast<float>(std::exp2(exposure_stops));
  const size_t pixels = rgb.size() / 3;
  rgba.resize(4 * pixels);
  for (size_t p = 0; p < pixels; ++p) {
    const std::array<uint8_t, 3> c =
        ToneMapPixel({rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]}, scale, kBackground);
    rgba[4 * p] = c[0];
    rgba[4 * p + 1] = c[1];
    rgba[4 * p + 2] = c[2];
    rgba[4 * p + 3] = 255;
  }
}

}  // namespace

struct RelightService::Session {
  struct Probe {
    EnvMap env;
    EnvProjector projector;
  };

  std::mutex mu;  // one frame at a time: the Relighter's scratch is per store
  bool opened = false;
  absl::Status open_error;
  std::optional<OpenedStore> store;
  std::unique_ptr<StoreView> view;
  std::vector<float> support;  // SupportSolidAngles(N), for per-frame selection
  std::map<std::string, std::unique_ptr<Probe>> probes;
  std::vector<float> cells, best, picture;

  absl::Status Open(const std::filesystem::path& path, const SceneLoader& scene) {
    if (opened) return open_error;
    opened = true;
    absl::StatusOr<OpenedStore> s = OpenStore(path);
    if (!s.ok()) return open_error = s.status();
    store.emplace(*std::move(s));
    absl::StatusOr<std::unique_ptr<StoreView>> v = MakeStoreView(*store, scene);
    if (!v.ok()) return open_error = v.status();
    view = *std::move(v);
    const Relighter& r = store->relighter;
    support = SupportSolidAngles(r.light_res());
    cells.resize(3 * static_cast<size_t>(r.cells()));
    best.resize(cells.size());
    picture.resize(3 * static_cast<size_t>(view->width()) * view->height());
    return absl::OkStatus();
  }

  absl::StatusOr<Probe*> ProbeFor(const ProbeCatalogue& catalogue, const std::string& name) {
    if (auto it = probes.find(name); it != probes.end()) return it->second.get();
    absl::StatusOr<std::string> spec = catalogue.Spec(name);
    if (!spec.ok()) return spec.status();
    absl::StatusOr<EnvMap> env = LoadEnvMap(*spec);
    if (!env.ok()) return env.status();
    const Relighter& r = store->relighter;
    absl::StatusOr<EnvProjector> projector =
        EnvProjector::Create(env->width, env->height, r.light_res(), r.row_filter());
    if (!projector.ok()) return projector.status();
    auto probe = std::make_unique<Probe>(Probe{*std::move(env), *std::move(projector)});
    return (probes[name] = std::move(probe)).get();
  }
};

RelightService::RelightService(ProbeCatalogue probes, size_t max_open_stores)
    : probes_(std::move(probes)), max_open_(std::max<size_t>(1, max_open_stores)) {}

RelightService::~RelightService() = default;

std::shared_ptr<RelightService::Session> RelightService::SessionFor(
    const std::filesystem::path& store) {
  const std::string key = store.lexically_normal().string();
  std::lock_guard lock(mu_);
  for (auto it = open_.begin(); it != open_.end(); ++it) {
    if (it->first != key) continue;
    open_.splice(open_.begin(), open_, it);
    return open_.front().second;
  }
  open_.emplace_front(key, std::make_shared<Session>());
  if (open_.size() > max_open_) open_.pop_back();  // a frame still running keeps its own
  return open_.front().second;
}

absl::StatusOr<RelightFrame> RelightService::Frame(const std::filesystem::path& path,
                                                   const SceneLoader& scene,
                                                   const RelightRequest& request) {
  if (absl::Status s = CheckRequest(request); !s.ok()) return s;
  std::shared_ptr<Session> session = SessionFor(path);
  std::lock_guard lock(session->mu);
  if (absl::Status s = session->Open(path, scene); !s.ok()) return s;
  absl::StatusOr<Session::Probe*> probe = session->ProbeFor(probes_, request.probe);
  if (!probe.ok()) return probe.status();
  Relighter& relighter = session->store->relighter;

  const auto start = std::chrono::steady_clock::now();
  std::optional<EnvMap> rotated;
  if (request.rotate_degrees != 0) rotated = Rotated((*probe)->env, request.rotate_degrees);
  absl::StatusOr<LightingCoefficients> lighting =
      (*probe)->projector.Project(rotated ? *rotated : (*probe)->env);
  if (!lighting.ok()) return lighting.status();
  absl::StatusOr<WaveletLights> lights =
      SelectWaveletLights(*lighting, request.terms, session->support);
  if (!lights.ok()) return lights.status();
  relighter.Relight(*lights, session->cells);
  session->view->Render(session->cells, session->picture);
  RelightFrame frame{.width = session->view->width(),
                     .height = session->view->height(),
                     .rgba = {},
                     .kind = session->view->kind(),
                     .terms = static_cast<int>(lights->lights.size()),
                     .columns = relighter.columns()};
  ToRgba(session->picture, request.exposure_stops, frame.rgba);
  frame.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (request.compare_all) {
    relighter.Relight(AllWaveletLights(*lighting), session->best);
    frame.rel_rms_all = CompareToReference(session->cells, session->best).rel_rms;
  }
  return frame;
}

}  // namespace wavebake::web
