#pragma once
/// Rotational part of a 3x3 deformation gradient F: the rotation R that
/// maximises tr(R^T F) (the polar rotation where det F > 0).
///
/// Iterative, after Mueller, Bender, Chentanez, Macklin, "A Robust Method to
/// Extract the Rotational Part of Deformations" (MIG 2016), warm-started from
/// the previous step's quaternion, with a Newton step added: with B = F R^T,
/// the gradient of tr(R^T F) under R <- exp([w]x) R is g = axial(B - B^T) and
/// its Hessian is H = tr(B) I - sym(B). Where H is positive definite (near the
/// optimum of any non-inverted F) the step is w = H^-1 g, which converges
/// quadratically; elsewhere it falls back to the paper's w = g / |tr(B)|, which
/// always makes progress. The update q <- normalize((1, w/2) q) rotates by
/// about |w| without trigonometry and has the same fixed point.
/// Always returns a proper rotation (det = +1), also for flat and inverted
/// elements. F is dimensionless, so the convergence threshold (1e-9 rad) means
/// the same at every mesh scale.
/// From the identity, 10^4 random rotations converge within 50 iterations;
/// warm-started in a simulation step, 1 to 3.
/// Limitation: from a start exactly opposite the optimum (a 180-degree flip)
/// the gradient vanishes and the start is returned; a warm start never is.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tcb {

/// Updates q in place to the rotation closest to F; returns iterations used.
int extract_rotation(const Eigen::Matrix3d& deformation_gradient, Eigen::Quaterniond& q, int max_iterations = 50);

}  // namespace tcb
