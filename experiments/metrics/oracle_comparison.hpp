#pragma once
/// A method's colliding points against the oracle's (docs/contract.md columns
/// recall, precision, depth_err_mean/max, oracle_points, max_depth).
///
/// Sets are of (object, vertex): M the method's colliding points, O the
/// oracle's strictly inside points, B the oracle's on-boundary points.
/// A vertex exactly on another object's surface is neither inside nor outside:
/// it counts as neither missed nor false (it is left out of both ratios).
///   recall    = |M n O| / |O|               (null when O is empty)
///   precision = |M n O| / |M \ B|           (null when M \ B is empty)
///   depth error = |d_method - d_true| over points in M n O that have a depth
///   on both sides (a self-collision point has a true depth only where the
///   body's parts define one, oracle/self_depth.hpp; NaN ones are left out);
///   the errors of self-collision points are also kept apart.

#include <optional>
#include <vector>

#include "method/handler/contact.hpp"
#include "oracle/inside_oracle.hpp"

namespace tcb {

struct OracleComparison {
  std::int64_t oracle_points = 0;
  std::optional<double> recall, precision, depth_err_mean, depth_err_max;
  double max_depth_m = 0.0;
  std::vector<double> depth_errors;       ///< every point both have a depth for
  std::vector<double> self_depth_errors;  ///< the self-collision ones among them
  std::int64_t self_points = 0;           ///< the oracle's self-collision points
  std::int64_t self_points_with_depth = 0;  ///< ... that have a true depth
};

OracleComparison compare_with_oracle(const std::vector<Contact>& method, const OracleFrame& oracle);

}  // namespace tcb
