#pragma once
// The relight view's server side (DESIGN.md §1 "Relighting"): a finished
// store relit under one of the catalogue's probes, turned about +Y, with the
// n most important wavelet lights, drawn as the store's picture
// (web/views/store_view.h) — and the same frame relit with every wavelet light,
// the store's best answer, so the page shows what the n-term approximation
// costs (the error of driver/relight/relight_sequence.h).
//
// Opened stores stay in memory (a few, least recently used first out); one
// frame at a time per store, frames of different stores in parallel.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "web/views/probe_catalogue.h"
#include "web/views/store_view.h"

namespace wavebake::web {

struct RelightRequest {
  std::string probe = "builtin:sky";  // a name of the catalogue
  double rotate_degrees = 0;
  int terms = 256;            // 1.. ; more than 6N² means all of them
  double exposure_stops = 0;  // display only, −20..20
  bool compare_all = true;    // also relight with every wavelet light
};

struct RelightFrame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // [4·width·height] 8-bit sRGB, row 0 at the top
  PictureKind kind = PictureKind::kGridImage;
  int terms = 0;            // wavelet lights used
  int columns = 0;          // 6N²: all of them
  double rel_rms_all = -1;  // relative RMS vs all wavelet lights over unmasked cells; −1 not asked
  double seconds = 0;       // lighting, relighting and picture (not the comparison)
};

class RelightService {
 public:
  explicit RelightService(ProbeCatalogue probes, size_t max_open_stores = 4);
  ~RelightService();
  const ProbeCatalogue& probes() const { return probes_; }

  using SceneLoader = std::function<absl::StatusOr<Scene>()>;
  // Errors: the request (named by field: probe, terms, rotate, exposure),
  // the store (not one, damaged), the scene of a mesh store.
  absl::StatusOr<RelightFrame> Frame(const std::filesystem::path& store, const SceneLoader& scene,
                                     const RelightRequest& request);

 private:
  struct Session;
  std::shared_ptr<Session> SessionFor(const std::filesystem::path& store);

  const ProbeCatalogue probes_;
  const size_t max_open_;
  std::mutex mu_;
  std::list<std::pair<std::string, std::shared_ptr<Session>>> open_;  // most recent first
};

}  // namespace wavebake::web
