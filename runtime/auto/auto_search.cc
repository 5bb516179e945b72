#include "runtime/auto/auto_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wavebake {
namespace {

// The compression share of the budget: what e_comp may be at this e_disc.
double CompressionBudget(const AutoSearchConfig& config, double e_disc) {
  const double e = config.target_error;
  return config.safety * std::sqrt(std::max(0.0, e * e - e_disc * e_disc));
}

}  // namespace

std::optional<double> ColumnTargetFor(const AutoSearchConfig& config, double e_disc) {
  if (!(e_disc <= config.disc_share * config.target_error)) return std::nullopt;
  return std::max(config.min_column_target, CompressionBudget(config, e_disc));
}

std::optional<double> TightenedColumnTarget(const AutoSearchConfig& config, double e_disc,
                                            double column_target, double e_tot) {
  // e_tot ≤ e_disc can only come from the reference's noise; then shrink by
  // the floor factor.
  const double e_comp = std::sqrt(std::max(0.0, e_tot * e_tot - e_disc * e_disc));
  const double scaled =
      e_comp > 0 ? column_target * CompressionBudget(config, e_disc) / e_comp : column_target;
  const double target = std::min(scaled, 0.7 * column_target);
  if (target < config.min_column_target) return std::nullopt;
  return target;
}

std::optional<double> LoosenedColumnTarget(const AutoSearchConfig& config, double e_disc,
                                           double column_target, double e_tot) {
  const double e_comp = std::sqrt(std::max(0.0, e_tot * e_tot - e_disc * e_disc));
  const double budget = CompressionBudget(config, e_disc);
  const double factor =
      e_comp > 0 ? std::min(config.max_loosen, budget / e_comp) : config.max_loosen;
  const double target = std::min(1.0, column_target * factor);
  if (target < config.min_loosen * column_target) return std::nullopt;
  return target;
}

AutoSearch::AutoSearch(AutoSearchConfig config) : config_(std::move(config)) {}

AutoAction AutoSearch::Next() const {
  if (chosen_) return {.step = AutoStep::kDone};
  if (res_index_ >= config_.resolutions.size())
    return {.step = AutoStep::kFailed, .reason = FailureReason()};
  const int n = config_.resolutions[res_index_];
  if (!e_disc_) return {.step = AutoStep::kMeasureDisc, .light_res = n};
  return {.step = AutoStep::kBake, .light_res = n, .column_target = *next_target_};
}

void AutoSearch::OnDisc(double e_disc) {
  AutoCandidate c;
  c.light_res = config_.resolutions[res_index_];
  c.e_disc = e_disc;
  candidates_.push_back(c);
  next_target_ = ColumnTargetFor(config_, e_disc);
  if (!next_target_) return Advance();
  e_disc_ = e_disc;
}

void AutoSearch::OnBaked(const AutoBakeMeasurement& m) {
  // The first bake at N completes the row OnDisc began; a retry adds one.
  if (candidates_.back().baked) {
    const AutoCandidate retry = candidates_.back();
    candidates_.push_back(retry);
  }
  AutoCandidate& c = candidates_.back();
  c.baked = true;
  c.column_target = *next_target_;
  c.bake = m;
  c.meets = m.e_tot <= config_.target_error;
  const size_t row = candidates_.size() - 1;
  if (c.meets && (!best_ || c.bake.bytes < candidates_[*best_].bake.bytes)) best_ = row;
  if (c.meets && bakes_ == 0 && !loosening_) {
    next_target_ = LoosenedColumnTarget(config_, c.e_disc, c.column_target, m.e_tot);
    loosening_ = next_target_.has_value();
    if (loosening_) return;
  }
  if (best_) {  // met E here (a loosened bake that missed keeps the first)
    chosen_ = best_;
    return;
  }
  ++bakes_;
  next_target_ = TightenedColumnTarget(config_, c.e_disc, c.column_target, m.e_tot);
  if (bakes_ >= config_.bakes_per_resolution || !next_target_) Advance();
}

void AutoSearch::Advance() {
  ++res_index_;
  e_disc_.reset();
  next_target_.reset();
  bakes_ = 0;
  loosening_ = false;
}

std::string AutoSearch::FailureReason() const {
  const AutoCandidate* best = nullptr;
  for (const AutoCandidate& c : candidates_) {
    const double e = c.baked ? c.bake.e_tot : c.e_disc;
    if (!best || e < (best->baked ? best->bake.e_tot : best->e_disc)) best = &c;
  }
  char text[256];
  if (!best) {
    std::snprintf(text, sizeof text, "no light resolution to try");
  } else {
    std::snprintf(text, sizeof text,
                  "no light resolution up to %d meets target error %.4g; closest: N=%d with %s "
                  "%.4g",
                  config_.resolutions.back(), config_.target_error, best->light_res,
                  best->baked ? "e_tot" : "e_disc", best->baked ? best->bake.e_tot : best->e_disc);
  }
  return text;
}

}  // namespace wavebake
