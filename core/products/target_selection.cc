#include "core/products/target_selection.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/products/haar_affine.h"

namespace wavebake {
namespace {

double IntervalOverlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

// 2^e for a small integer e, without a libm call (per sample and level).
inline double ExactPow2Of(int e) { return std::bit_cast<double>(uint64_t(1023 + e) << 52); }

// ã: the coefficient of the 1D factor f for the indicator of [a, b].
double IntervalCoefficient(Haar1d f, double a, double b) {
  const double w = ExactPow2Of(-f.level), x0 = f.offset * w;
  const double norm = std::sqrt(ExactPow2Of(f.level));
  if (!f.wavelet) return norm * IntervalOverlap(a, b, x0, x0 + w);
  return norm * (IntervalOverlap(a, b, x0, x0 + w / 2) - IntervalOverlap(a, b, x0 + w / 2, x0 + w));
}

// One axis at one level: the factors whose support meets [a, b], and the
// (at most two) wavelets among them with a nonzero coefficient — the ones
// with an end of the interval inside.
struct AxisLevel {
  int first = 0, last = -1;  // offsets of the scaling functions that meet [a, b]
  int edges = 0;
  int edge[2] = {0, 0};
  double edge_value[2] = {0, 0};

  int count() const { return last - first + 1; }
  bool IsEdge(int t) const { return (edges > 0 && edge[0] == t) || (edges > 1 && edge[1] == t); }
};

AxisLevel Axis(int level, double a, double b) {
  const int count = 1 << level;
  AxisLevel al;
  al.first = std::clamp(static_cast<int>(std::floor(a * count)), 0, count - 1);
  al.last = std::clamp(static_cast<int>(std::ceil(b * count)) - 1, al.first, count - 1);
  for (double end : {a, b}) {
    const int t = std::clamp(static_cast<int>(std::floor(end * count)), al.first, al.last);
    if (al.IsEdge(t)) continue;
    const double v = IntervalCoefficient({true, level, t}, a, b);
    if (v == 0) continue;
    al.edge[al.edges] = t;
    al.edge_value[al.edges++] = v;
  }
  return al;
}

double Phi(int level, int t, double a, double b) {
  return IntervalCoefficient({false, level, t}, a, b);
}

}  // namespace

TargetSelector::TargetSelector(int n) : n_(n), levels_(0) {
  while ((1 << levels_) < n) ++levels_;
}

double TargetSelector::Prediction(double ax, double bx, double ay, double by, int m) const {
  const FactorPair f = NonStandardFactors(m % n_, m / n_);
  return IntervalCoefficient(f.x, ax, bx) * IntervalCoefficient(f.y, ay, by);
}

void TargetSelector::Select(double ax, double bx, double ay, double by, int budget,
                            std::vector<uint16_t>& out) {
  out.clear();
  ax = std::max(ax, 0.0), ay = std::max(ay, 0.0), bx = std::min(bx, 1.0), by = std::min(by, 1.0);
  if (!(bx > ax && by > ay) || budget <= 0) return;
  AxisLevel xs[16], ys[16];
  int64_t candidates = 1, predicted = 1;  // the scaling function is both
  for (int l = 0; l < levels_; ++l) {
    xs[l] = Axis(l, ax, bx);
    ys[l] = Axis(l, ay, by);
    const int64_t nx = xs[l].count(), ny = ys[l].count(), ex = xs[l].edges, ey = ys[l].edges;
    candidates += 3 * nx * ny;
    predicted += ex * ny + nx * ey + ex * ey;
  }
  const auto index = [&](int x, int y) { return static_cast<uint16_t>(y * n_ + x); };
  // Calls emit(index, in_predicted) for every candidate, coarse to fine,
  // until it returns false.
  const auto each_candidate = [&](const auto& emit) {
    if (!emit(index(0, 0), true)) return;
    for (int l = 0; l < levels_; ++l) {
      const int w = 1 << l;
      const AxisLevel &x = xs[l], &y = ys[l];
      for (int ty = y.first; ty <= y.last; ++ty)
        for (int tx = x.first; tx <= x.last; ++tx)
          if (!emit(index(w + tx, ty), x.IsEdge(tx))) return;  // ψ ⊗ φ
      for (int ty = y.first; ty <= y.last; ++ty)
        for (int tx = x.first; tx <= x.last; ++tx)
          if (!emit(index(tx, w + ty), y.IsEdge(ty))) return;  // φ ⊗ ψ
      for (int ty = y.first; ty <= y.last; ++ty)
        for (int tx = x.first; tx <= x.last; ++tx)
          if (!emit(index(w + tx, w + ty), x.IsEdge(tx) && y.IsEdge(ty))) return;  // ψ ⊗ ψ
    }
  };
  if (candidates <= budget) {
    each_candidate([&](uint16_t m, bool) { return out.push_back(m), true; });
    return;
  }
  if (predicted < budget) {  // every nonzero prediction, then the ties coarse first
    int64_t fill = budget - predicted;
    each_candidate([&](uint16_t m, bool nonzero) {
      if (nonzero) {
        out.push_back(m);
      } else if (fill > 0) {
        out.push_back(m);
        --fill;
      }
      return true;
    });
    return;
  }
  // More nonzero predictions than the budget: the largest |L̃| (the edges).
  scored_.clear();
  scored_.push_back({static_cast<float>((bx - ax) * (by - ay)), index(0, 0)});
  for (int l = 0; l < levels_; ++l) {
    const int w = 1 << l;
    const AxisLevel &x = xs[l], &y = ys[l];
    for (int e = 0; e < x.edges; ++e)
      for (int ty = y.first; ty <= y.last; ++ty)
        scored_.push_back({static_cast<float>(std::fabs(x.edge_value[e] * Phi(l, ty, ay, by))),
                           index(w + x.edge[e], ty)});
    for (int e = 0; e < y.edges; ++e)
      for (int tx = x.first; tx <= x.last; ++tx)
        scored_.push_back({static_cast<float>(std::fabs(Phi(l, tx, ax, bx) * y.edge_value[e])),
                           index(tx, w + y.edge[e])});
    for (int ex = 0; ex < x.edges; ++ex)
      for (int ey = 0; ey < y.edges; ++ey)
        scored_.push_back({static_cast<float>(std::fabs(x.edge_value[ex] * y.edge_value[ey])),
                           index(w + x.edge[ex], w + y.edge[ey])});
  }
  std::nth_element(scored_.begin(), scored_.begin() + (budget - 1), scored_.end(),
                   [](const Scored& a, const Scored& b) {
                     return a.score != b.score ? a.score > b.score : a.index < b.index;
                   });
  for (int j = 0; j < budget; ++j) out.push_back(scored_[j].index);
}

}  // namespace wavebake
