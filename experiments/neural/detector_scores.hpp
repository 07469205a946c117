#pragma once
/// How a detector's verdicts compare with exact labels on a held-out set:
/// the confusion counts and the rates the seed reports. A code is predicted
/// colliding when the network's logit is > 0 (sigmoid > 0.5). Rates with an
/// empty denominator are NaN (written as empty cells).

#include <cstdint>
#include <vector>

#include "method/neural/active_learning.hpp"

namespace tcb {

struct DetectorScores {
  std::int64_t true_positive = 0, false_positive = 0, true_negative = 0, false_negative = 0;
  double accuracy() const;
  double false_negative_rate() const;  ///< missed collisions / collisions
  double false_positive_rate() const;  ///< false alarms / collision-free codes
  double precision() const;
  double recall() const;
};

DetectorScores score_detector(const neural::Mlp<double>& net, const std::vector<neural::Sample>& test_set);

}  // namespace tcb
