#include "driver/relight/relight_sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/incremental.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/atomic_file.h"

namespace wavebake::driver {
namespace {

absl::Status BadSequence(std::string_view spec, const char* why) {
  return absl::InvalidArgumentError(
      absl::StrCat("rotate-sequence: '", std::string(spec), "' ", why, " (START:END:FRAMES)"));
}

}  // namespace

std::filesystem::path SequenceFramePath(const std::filesystem::path& dir, int index,
                                        std::string_view extension) {
  return dir / absl::StrFormat("frame_%04d%s", index, extension);
}

absl::StatusOr<RotateSequence> ParseRotateSequence(std::string_view spec) {
  const std::vector<std::string> parts = absl::StrSplit(std::string(spec), ':');
  if (parts.size() != 3) return BadSequence(spec, "needs three fields");
  RotateSequence r;
  if (!absl::SimpleAtod(parts[0], &r.start_degrees) || !std::isfinite(r.start_degrees) ||
      !absl::SimpleAtod(parts[1], &r.end_degrees) || !std::isfinite(r.end_degrees))
    return BadSequence(spec, "has a START or END that is not a finite number of degrees");
  if (!absl::SimpleAtoi(parts[2], &r.frames) || r.frames < 1 || r.frames > 100000)
    return BadSequence(spec, "needs FRAMES in 1..100000");
  return r;
}

absl::StatusOr<std::vector<SequenceFrame>> RelightSequence(const std::filesystem::path& store,
                                                           std::string_view env_spec,
                                                           const SequenceOptions& o) {
  if (o.terms <= 0) return absl::InvalidArgumentError(absl::StrCat("terms: ", o.terms, " < 1"));
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  if (absl::Status s = RequireCubeDomain(opened->info); !s.ok()) return s;
  Relighter& relighter = opened->relighter;
  std::optional<IncrementalRelighter> incremental;
  if (o.mode != SequenceMode::kNonIncremental) {
    const IncrementalPolicy policy =
        o.mode == SequenceMode::kBasic ? IncrementalPolicy::kBasic : IncrementalPolicy::kPerBand;
    absl::StatusOr<IncrementalRelighter> inc =
        IncrementalRelighter::Create(&relighter, o.terms, policy);
    if (!inc.ok()) return inc.status();
    incremental.emplace(*std::move(inc));
  }
  if (!o.out_dir.empty()) {
    if (absl::Status s = CreateDirectories(o.out_dir); !s.ok()) return s;
  }

  const size_t values = 3 * static_cast<size_t>(relighter.cells());
  std::vector<float> frame(values), best(values);
  std::vector<SequenceFrame> frames;
  const RotateSequence& rot = o.rotation;
  absl::StatusOr<EnvProjector> projector =
      EnvProjector::Create(env->width, env->height, relighter.light_res(), relighter.row_filter());
  if (!projector.ok()) return projector.status();
  for (int i = 0; i < rot.frames; ++i) {
    SequenceFrame f{.index = i};
    f.degrees =
        rot.start_degrees + (rot.end_degrees - rot.start_degrees) * i / std::max(rot.frames - 1, 1);
    const auto t0 = std::chrono::steady_clock::now();
    absl::StatusOr<LightingCoefficients> lighting = projector->Project(Rotated(*env, f.degrees));
    if (!lighting.ok()) return lighting.status();
    if (incremental) {
      if (absl::Status s = incremental->Frame(*lighting, frame); !s.ok()) return s;
    } else {
      absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, o.terms);
      if (!lights.ok()) return lights.status();
      relighter.Relight(*lights, frame);
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    relighter.Relight(AllWaveletLights(*lighting), best);
    absl::StatusOr<ErrorStats> error = CompareFinite(frame, best, absl::StrCat("frame ", i));
    if (!error.ok()) return error.status();
    f.rel_rms = error->rel_rms;
    frames.push_back(f);
    if (!o.out_dir.empty()) {
      if (absl::Status s = WriteRelit(*opened, frame, o.exposure_stops,
                                      SequenceFramePath(o.out_dir, i, o.frame_extension));
          !s.ok())
        return s;
    }
  }
  if (!o.out_dir.empty()) {
    if (absl::Status s = WriteErrorsCsv(
            o.out_dir, "degrees", std::span<const SequenceFrame>(frames), &SequenceFrame::degrees);
        !s.ok())
      return s;
  }
  return frames;
}

SequenceSummary Summarize(std::span<const SequenceFrame> frames) {
  SequenceSummary sum;
  if (frames.empty()) return sum;
  for (const SequenceFrame& f : frames) {
    sum.mean_rel_rms += f.rel_rms;
    sum.max_rel_rms = std::max(sum.max_rel_rms, f.rel_rms);
    sum.mean_seconds += f.seconds;
  }
  sum.mean_rel_rms /= static_cast<double>(frames.size());
  sum.mean_seconds /= static_cast<double>(frames.size());
  return sum;
}

}  // namespace wavebake::driver
