#pragma once
/// Divergence of a run from a reference run of the same scene (issue 20):
/// how far the states of two runs are apart at the same step. Kernel of
/// divergence_meter.hpp, on plain per-body arrays.
///
/// Over the dynamic bodies (passive ones are the scene's, not the run's):
///   rms_m, max_m        RMS and max over vertices of |x - x_ref|
///   com_drift_m         max over bodies of the distance between the two
///                       mass-weighted centres
///   orientation_drift_deg  max over bodies of the angle of the best-fit
///                       rotation taking the reference body onto the run's
///                       (mass-weighted, about each centre; Kabsch, with the
///                       reflection removed); 0 for bodies of < 3 vertices
///   linear_momentum_diff_n_s    max over bodies of |p - p_ref|, p = sum m v
///   angular_momentum_diff_n_m_s max over bodies of |L - L_ref|, L = sum
///                       m (x - c) x v about the body's own centre
/// Units SI. The same state gives exactly 0 in every field; a non-finite
/// state gives NaN in every field.

#include <vector>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct Divergence {
  double rms_m = 0.0, max_m = 0.0, com_drift_m = 0.0, orientation_drift_deg = 0.0;
  double linear_momentum_diff_n_s = 0.0, angular_momentum_diff_n_m_s = 0.0;
};

struct StateView {
  const std::vector<std::vector<Vec3>>& x_m;
  const std::vector<std::vector<Vec3>>& v_m_per_s;
};

/// `dynamic[b]` says which bodies count; masses per body and vertex (kg).
/// Bodies and vertex counts must agree (std::invalid_argument otherwise).
Divergence compare_states(const StateView& run, const StateView& reference,
                          const std::vector<std::vector<double>>& masses_kg, const std::vector<char>& dynamic);

}  // namespace tcb
