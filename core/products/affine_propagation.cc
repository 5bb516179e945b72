#include "core/products/affine_propagation.h"

#include <algorithm>

namespace wavebake {
namespace {

// Slot of `id` in the distinct factors of one axis, adding it if new.
uint16_t SlotOf(std::vector<uint16_t>& factors, uint16_t id) {
  const auto it = std::find(factors.begin(), factors.end(), id);
  if (it != factors.end()) return static_cast<uint16_t>(it - factors.begin());
  factors.push_back(id);
  return static_cast<uint16_t>(factors.size() - 1);
}

}  // namespace

AffinePropagator::AffinePropagator(std::span<const SourceTerm> sources, int source_res,
                                   int target_res, const CouplingTable* table)
    : source_res_(source_res),
      target_res_(target_res),
      target_factors_(Haar1dCount(target_res)),
      table_(table) {
  // Discrete coefficients on both sides (the header): L = (N/R) Σ F D.
  const float scale = static_cast<float>(target_res) / static_cast<float>(source_res);
  for (const SourceTerm& t : sources) {
    const FactorPair f = NonStandardFactors(t.x, t.y);
    terms_.push_back({SlotOf(x_.factor, static_cast<uint16_t>(Haar1dId(f.x))),
                      SlotOf(y_.factor, static_cast<uint16_t>(Haar1dId(f.y))),
                      {t.rgb[0] * scale, t.rgb[1] * scale, t.rgb[2] * scale, 0}});
  }
  for (Axis* a : {&x_, &y_}) {
    a->owned.resize(a->factor.size());
    a->couplings.resize(a->factor.size());
  }
  const int texels = target_res * target_res;
  target_x_.resize(texels);
  target_y_.resize(texels);
  target_y_wavelet_.resize(texels);
  for (int m = 0; m < texels; ++m) {
    const FactorPair f = NonStandardFactors(m % target_res, m / target_res);
    target_x_[m] = static_cast<uint16_t>(Haar1dId(f.x));
    target_y_[m] = static_cast<uint16_t>(Haar1dId(f.y));
    target_y_wavelet_[m] = f.y.wavelet || m == 0;
  }
  z_by_y_.assign(y_.factor.size() * target_factors_, Rgb4{});
  z_by_x_.assign(x_.factor.size() * target_factors_, Rgb4{});
}

void AffinePropagator::Couple(Axis& axis, double s, double o) {
  for (size_t slot = 0; slot < axis.factor.size(); ++slot) {
    if (table_) {
      axis.couplings[slot] = table_->Lookup(axis.factor[slot], s, o);
    } else {
      axis.owned[slot].clear();
      SourceCouplings(Haar1dOf(axis.factor[slot]), s, o, target_res_, axis.owned[slot]);
      axis.couplings[slot] = axis.owned[slot];
    }
  }
}

void AffinePropagator::Accumulate(const Axis& along, bool along_x, std::vector<Rgb4>& partial) {
  for (const Term& t : terms_) {
    Rgb4* row = &partial[size_t(along_x ? t.y_slot : t.x_slot) * target_factors_];
    for (const Coupling1d& c : along.couplings[along_x ? t.x_slot : t.y_slot]) {
      Rgb4& z = row[c.target];
      for (int ch = 0; ch < 4; ++ch) z[ch] += t.rgb[ch] * c.value;
    }
  }
}

void AffinePropagator::Clear(const Axis& along, bool along_x, std::vector<Rgb4>& partial) {
  for (const Term& t : terms_) {
    Rgb4* row = &partial[size_t(along_x ? t.y_slot : t.x_slot) * target_factors_];
    for (const Coupling1d& c : along.couplings[along_x ? t.x_slot : t.y_slot]) row[c.target] = {};
  }
}

void AffinePropagator::Invert(const Axis& axis, std::vector<uint32_t>& first,
                              std::vector<Bucket>& buckets) {
  first.assign(target_factors_ + 1, 0);
  for (const auto& list : axis.couplings)
    for (const Coupling1d& c : list) ++first[c.target + 1];
  for (int k = 0; k < target_factors_; ++k) first[k + 1] += first[k];
  buckets.resize(first.back());
  std::vector<uint32_t>& fill = first;  // advanced to each bucket's end, then restored
  for (size_t slot = 0; slot < axis.couplings.size(); ++slot)
    for (const Coupling1d& c : axis.couplings[slot])
      buckets[fill[c.target]++] = {static_cast<uint16_t>(slot), c.value};
  for (int k = target_factors_; k > 0; --k) fill[k] = fill[k - 1];
  fill[0] = 0;
}

void AffinePropagator::Propagate(const AffineMap2d& map, std::span<const uint16_t> targets,
                                 std::span<float> rgb_out) {
  Couple(x_, map.s_x, map.o_x);
  Couple(y_, map.s_y, map.o_y);
  Accumulate(x_, true, z_by_y_);   // step 1 along x, for step 2 along y
  Accumulate(y_, false, z_by_x_);  // step 1 along y, for step 2 along x
  Invert(y_, first_y_, buckets_y_);
  Invert(x_, first_x_, buckets_x_);
  const int f = target_factors_;
  for (size_t j = 0; j < targets.size(); ++j) {
    const int m = targets[j];
    Rgb4 sum{};
    if (target_y_wavelet_[m]) {
      const Rgb4* z = &z_by_y_[target_x_[m]];
      for (uint32_t b = first_y_[target_y_[m]], e = first_y_[target_y_[m] + 1]; b < e; ++b) {
        const Rgb4& v = z[size_t(buckets_y_[b].slot) * f];
        for (int ch = 0; ch < 4; ++ch) sum[ch] += v[ch] * buckets_y_[b].value;
      }
    } else {
      const Rgb4* z = &z_by_x_[target_y_[m]];
      for (uint32_t b = first_x_[target_x_[m]], e = first_x_[target_x_[m] + 1]; b < e; ++b) {
        const Rgb4& v = z[size_t(buckets_x_[b].slot) * f];
        for (int ch = 0; ch < 4; ++ch) sum[ch] += v[ch] * buckets_x_[b].value;
      }
    }
    for (int ch = 0; ch < 3; ++ch) rgb_out[3 * j + ch] = sum[ch];
  }
  Clear(x_, true, z_by_y_);
  Clear(y_, false, z_by_x_);
}

}  // namespace wavebake
