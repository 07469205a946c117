#pragma once
/// A penalty contact handed to the integrator instead of as a force, so its
/// spring and damper are integrated implicitly with the bodies (the implicit
/// response mode, method/handler/collision_settings.hpp).
///
/// Vertex `vertex` of body `point_body` lies inside a tet of `tet_body` at
/// barycentric `weights` of its vertices `tet_vertices`. With the relative
/// velocity g = v_point - sum_k w_k v_tet_k and s = n . g, the normal force on
/// the point at the end of the step is
///   lambda n,  lambda = k (d - h s+) - c s+
/// (d the depth at the start of the step, h the step, s+ with the new
/// velocities): linear in the new velocities, so it enters the implicit Euler
/// system as h (h k + c) J^T n n^T J on the left and h k d J^T n on the right.
/// The reaction -w_k lambda n goes to the tet's vertices (momentum is
/// conserved). A passive or driven side enters through its known velocity
/// only. Contacts are unilateral: a link whose lambda comes out negative
/// (it would pull) is dropped and the system solved once more. Units SI.

#include <array>
#include <cstdint>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct ContactLink {
  std::int32_t point_body = -1, vertex = -1;
  std::int32_t tet_body = -1;
  std::array<std::int32_t, 4> tet_vertices{};
  std::array<double, 4> weights{};  ///< barycentric, sum to 1
  Vec3 normal = Vec3::Zero();       ///< unit, pushes the point out of the tet's body
  double depth_m = 0.0;             ///< > 0
  double stiffness_n_per_m = 0.0;
  double damping_n_s_per_m = 0.0;
};

/// lambda of a link for the normal relative velocity s+ = n . (v_point -
/// sum_k w_k v_tet_k) at the end of a step of dt_s (N; < 0: it would pull).
inline double link_lambda(const ContactLink& link, double normal_velocity_m_per_s, double dt_s) {
  return link.stiffness_n_per_m * (link.depth_m - dt_s * normal_velocity_m_per_s) -
         link.damping_n_s_per_m * normal_velocity_m_per_s;
}

}  // namespace tcb
