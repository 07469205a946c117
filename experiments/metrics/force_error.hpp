#pragma once
/// Force error (issue 20): the contact forces a method applied in a step
/// against those full handling would have applied in the same step from the
/// same state (the force reference, force_reference_meter.hpp).
///
/// Inputs are per-body, per-vertex force fields (N): what contacts applied
/// in the step, their own forces and the reactions on tet vertices alike
/// (Body::applied_contact_force_n: explicit forces, or under implicit
/// response the links' solved forces), and the points each side gave a
/// force of their own, the method's with the source of that force.
///
/// Definitions:
///   relative_l2  ||F_m - F_r|| / ||F_r||, norms over every vertex of every
///                body; 0 when both fields are zero; none when only the
///                reference is zero (nothing to be relative to: every applied
///                force is a ghost)
///   missed       reference points the method gave no force
///   ghosts       method points with no reference point
///   angle_deg    per point in both sets whose two forces are both non-zero:
///                the angle between F_m and F_r at that vertex (degrees,
///                atan2(|a x b|, a . b), well conditioned near 0 and 180)
///   by_source    per ForceSource of the method's points: their count, their
///                ghosts, their angles, and squared_error_n2, the sum over
///                them of |F_m - F_r|^2 (sqrt(that) / ||F_r|| is their part of
///                relative_l2; the parts add up in quadrature with the
///                reaction-only and missed vertices)
/// A point listed twice counts once, with its first source.

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "method/handler/collision_handler.hpp"

namespace tcb {

using ForceField = std::vector<std::vector<Vec3>>;

struct SourceForceError {
  std::int64_t points = 0, ghosts = 0;
  double squared_error_n2 = 0.0;
  std::vector<double> angle_deg;
};

struct ForceError {
  std::optional<double> relative_l2;
  double reference_norm_n = 0.0;
  std::int64_t reference_points = 0, applied_points = 0, missed = 0, ghosts = 0;
  std::vector<double> angle_deg;
  std::array<SourceForceError, kForceSources> by_source{};
};

/// Compares the method's field and points with the reference's (same body
/// and vertex counts; std::invalid_argument otherwise).
ForceError compare_forces(const ForceField& applied, const std::vector<ForcePoint>& applied_points,
                          const ForceField& reference, const std::vector<ForcePoint>& reference_points);

/// "computed", "held", "extrapolated", "tracked".
const char* force_source_name(ForceSource source);

}  // namespace tcb
