#pragma once
/// The four training losses of seed 002 (N-Penetrate §4.3) on logits r (one
/// per sample; colliding when r > 0). Each returns its mean over the samples
/// it is given and writes dL/dr per sample; empty input gives loss 0 and an
/// empty gradient. Which samples each gets is the trainer's choice
/// (active_learning.hpp): depth regression the penetrating ones, the
/// boundary term the barely penetrating ones.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Dense>

namespace tcb::neural {

template <class S>
using LossVec = Eigen::Matrix<S, Eigen::Dynamic, 1>;

/// Binary cross-entropy of sigmoid(r) against labels in {0, 1}, evaluated
/// as softplus(r) - y r (no overflow for any r).
template <class S>
S cross_entropy(const LossVec<S>& r, const LossVec<S>& label, LossVec<S>& dloss_dr) {
  const Eigen::Index n = r.size();
  dloss_dr.resize(n);
  if (n == 0) return S(0);
  S loss(0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const S x = r[i];
    loss += std::max(x, S(0)) + std::log1p(std::exp(-std::abs(x))) - label[i] * x;
    const S sigmoid = x >= S(0) ? S(1) / (S(1) + std::exp(-x)) : std::exp(x) / (S(1) + std::exp(x));
    dloss_dr[i] = (sigmoid - label[i]) / S(n);
  }
  return loss / S(n);
}

/// (r - depth / depth_scale)^2: the logit as a differentiable stand-in for
/// the penetration depth.
template <class S>
S depth_regression(const LossVec<S>& r, const LossVec<S>& depth, S depth_scale, LossVec<S>& dloss_dr) {
  const Eigen::Index n = r.size();
  dloss_dr.resize(n);
  if (n == 0) return S(0);
  const LossVec<S> e = r - depth / depth_scale;
  dloss_dr = S(2) * e / S(n);
  return e.squaredNorm() / S(n);
}

/// Marginal ranking over every ordered pair with depth_i > depth_j:
/// max(0, margin - (r_i - r_j)), averaged over those pairs (0 when there are
/// none). O(n^2) time, O(n) memory.
template <class S>
S ranking(const LossVec<S>& r, const LossVec<S>& depth, S margin, LossVec<S>& dloss_dr) {
  const Eigen::Index n = r.size();
  dloss_dr = LossVec<S>::Zero(n);
  std::int64_t pairs = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) pairs += depth[i] > depth[j];
  if (pairs == 0) return S(0);
  S loss(0);
  const S w = S(1) / S(pairs);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!(depth[i] > depth[j])) continue;
      const S h = margin - (r[i] - r[j]);
      if (h <= S(0)) continue;
      loss += h;
      dloss_dr[i] -= w, dloss_dr[j] += w;
    }
  return loss * w;
}

/// r^2: barely penetrating samples belong on the decision boundary (r = 0).
template <class S>
S boundary(const LossVec<S>& r, LossVec<S>& dloss_dr) {
  const Eigen::Index n = r.size();
  dloss_dr.resize(n);
  if (n == 0) return S(0);
  dloss_dr = S(2) * r / S(n);
  return r.squaredNorm() / S(n);
}

}  // namespace tcb::neural
