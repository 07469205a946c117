#pragma once
/// The ground: the half-space y < height is solid. Resolved after each
/// integration step at the velocity level, per vertex:
///   a vertex below the plane is put back on it (y = height); if it moves into
///   the ground (v_y < 0) the normal velocity is removed (inelastic) and the
///   tangential velocity is reduced by at most friction * |removed v_y|
///   (Coulomb: sticks when the tangential speed is below that bound).
/// This is a projection, not a penalty force: it adds no stiffness and so
/// never limits the time step. Units: m, m/s.

#include <span>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

struct GroundPlane {
  double height_m = 0.0;
  double friction = 0.5;  ///< Coulomb coefficient, >= 0
};

/// Projects the vertices below the ground; returns how many were touched.
std::size_t apply_ground(const GroundPlane& ground, std::span<Vec3> x_m, std::span<Vec3> v_m_per_s);

}  // namespace tcb
