#include "experiments/neural/detector_scores.hpp"

#include <limits>

namespace tcb {
namespace {

double ratio(std::int64_t a, std::int64_t b) {
  return b == 0 ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(a) / static_cast<double>(b);
}

}  // namespace

double DetectorScores::accuracy() const {
  return ratio(true_positive + true_negative, true_positive + true_negative + false_positive + false_negative);
}
double DetectorScores::false_negative_rate() const { return ratio(false_negative, true_positive + false_negative); }
double DetectorScores::false_positive_rate() const { return ratio(false_positive, false_positive + true_negative); }
double DetectorScores::precision() const { return ratio(true_positive, true_positive + false_positive); }
double DetectorScores::recall() const { return ratio(true_positive, true_positive + false_negative); }

DetectorScores score_detector(const neural::Mlp<double>& net, const std::vector<neural::Sample>& test_set) {
  DetectorScores s;
  if (test_set.empty()) return s;
  Eigen::MatrixXd z(test_set.front().z.size(), static_cast<Eigen::Index>(test_set.size()));
  for (std::size_t i = 0; i < test_set.size(); ++i) z.col(static_cast<Eigen::Index>(i)) = test_set[i].z;
  const Eigen::MatrixXd r = net.forward_batch(z);
  for (std::size_t i = 0; i < test_set.size(); ++i) {
    const bool predicted = r(0, static_cast<Eigen::Index>(i)) > 0.0;
    const bool actual = test_set[i].label.collides;
    (predicted ? (actual ? s.true_positive : s.false_positive) : (actual ? s.false_negative : s.true_negative))++;
  }
  return s;
}

}  // namespace tcb
