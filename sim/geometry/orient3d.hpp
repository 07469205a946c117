#pragma once
/// Exact 3D orientation predicate.
///
/// Computes the sign of the determinant det[b-a, c-a, d-a], i.e. the sign of
/// six times the signed volume of the tetrahedron (a, b, c, d):
///   +1  d lies on the side of plane(a, b, c) that (b-a) x (c-a) points to
///       (the tet (a, b, c, d) is positively oriented),
///    0  the four points are exactly coplanar,
///   -1  otherwise.
/// The answer is exact for double inputs (no epsilon): a floating-point filter
/// (Shewchuk 1997, error bound of orient3d stage A) answers the easy cases;
/// when it cannot certify the sign, the determinant is evaluated exactly in
/// floating-point expansion arithmetic (Shewchuk's Two-Sum/Two-Product,
/// Fast-Expansion-Sum, Scale-Expansion with zero elimination).
///
/// Contract: exact when no intermediate product over- or underflows, i.e. for
/// finite coordinates whose magnitudes are 0 or lie within about [1e-90, 1e90]
/// (then every coordinate difference is a multiple of 2^-352, every product
/// of three and each of its exact parts a multiple of 2^-1056, above the
/// smallest subnormal, and none overflows).
/// Requires IEEE-754 round-to-nearest-even doubles without -ffast-math.
/// Between the filter and the expansions, an exact shortcut returns 0 when
/// every term of the determinant has an exactly zero coordinate difference
/// (e.g. four points in one axis-aligned plane); a second one, when two of
/// a, b, c share d's coordinate on one axis and the third does not, answers
/// from the third one's difference on that axis (its sign) times a 2x2
/// cross_product_sign() (filtered, exact); then, when the nine coordinate
/// differences are exact, an accurate sum of the determinant's 24 exact
/// parts with a proven error bound decides most of the rest
/// (orient3d_exact_differences).
/// Cost: ~20 flops when the filter decides, a few more when a shortcut
/// does (the second one's 2x2 has its own filter, and its own expansions
/// for a minor that nearly cancels); a few hundred, with a dozen
/// well-predicted exits, when the summation stage does; a few hundred with
/// data-dependent branches when the expansions must (inexact differences
/// with a determinant too small for the filter, or a sign the stage leaves
/// open).

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tcb {

/// Relative error bound of orient3d's floating-point evaluation (Shewchuk's
/// orient3d "stage A"), times the permanent of the differences.
inline constexpr double kOrient3dErrorBound = (7.0 + 56.0 * 0x1p-53) * 0x1p-53;

/// orient3d's floating-point filter alone, on the differences already
/// taken: ad = a - d, bd = b - d, cd = c - d (as doubles, rounded as
/// written). Returns orient3d(a, b, c, d)'s sign (+1 or -1) when the filter
/// certifies it, and 0 when it cannot decide (then call orient3d(), or
/// orient3d_unfiltered() to skip the filter, which decide exactly, zero
/// included). It is the very evaluation and bound
/// orient3d() starts with, so it never answers differently; inline so that
/// a caller testing one point against several faces (point in tet) takes
/// the point's differences once and pays no call for the easy faces.
/// The bound assumes every product and sum is rounded where written: a
/// translation unit calling it must not fuse multiply-adds
/// (-ffp-contract=off where the target has FMA; the CMake files set it on
/// every file that calls it: orient3d.cpp, perturbed_predicates.cpp and its
/// test).
inline int orient3d_filter(const Eigen::Vector3d& ad, const Eigen::Vector3d& bd, const Eigen::Vector3d& cd) {
  const double bdycdz = bd.y() * cd.z(), bdzcdy = bd.z() * cd.y();
  const double cdyadz = cd.y() * ad.z(), cdzady = cd.z() * ad.y();
  const double adybdz = ad.y() * bd.z(), adzbdy = ad.z() * bd.y();
  const double det = ad.x() * (bdycdz - bdzcdy) + bd.x() * (cdyadz - cdzady) + cd.x() * (adybdz - adzbdy);
  const double permanent = (std::fabs(bdycdz) + std::fabs(bdzcdy)) * std::fabs(ad.x()) +
                           (std::fabs(cdyadz) + std::fabs(cdzady)) * std::fabs(bd.x()) +
                           (std::fabs(adybdz) + std::fabs(adzbdy)) * std::fabs(cd.x());
  const double bound = kOrient3dErrorBound * permanent;
  // det[a-d, b-d, c-d] = -det[b-a, c-a, d-a]: the signs swap.
  if (det > bound) return -1;
  if (-det > bound) return 1;
  return 0;
}

/// Sign (+1, 0, -1) of det[b-a, c-a, d-a]; exact. See the file comment.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d);

/// orient3d() past its filter (the shortcuts, the summation stage, the
/// expansions): the same exact sign for any input within the contract above
/// (NaN, infinite or out-of-range coordinates get no promise: a shortcut and
/// the expansions may then answer differently), meant for a caller that
/// ran orient3d_filter() itself and got 0, so the filter is not evaluated
/// twice.
int orient3d_unfiltered(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& d);

/// Whether orient3d_exact_differences() may use the processor's fused
/// multiply-add (two instructions a product's exact parts; Dekker's
/// splitting takes about 17): on x86 when the processor has it, elsewhere
/// never. The answer is the same either way; Never is for tests of the
/// other build.
enum class FusedMultiplyAdd { IfAvailable, Never };

/// orient3d's stage between the shortcut and the expansions, exposed so
/// tests can check it against orient3d_exact. When the nine differences
/// a-d, b-d, c-d are exact doubles (as for nearby points: Sterbenz), the
/// determinant is the exact sum of 24 doubles (Two-Product twice per
/// Leibniz term). Their sum by Sum2 (Ogita, Rump and Oishi 2005) with its
/// proven error bound decides the sign when the determinant is not below
/// about 2^-96 of the terms' magnitudes; else up to two more error-free
/// passes (VecSum) try to certify it, zero included. Returns whether it
/// decided, and then sets `sign` to orient3d's sign (exactly); false when a
/// difference is inexact or the sign stays open. Same range contract as
/// orient3d.
bool orient3d_exact_differences(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                const Eigen::Vector3d& d, int& sign,
                                FusedMultiplyAdd fma = FusedMultiplyAdd::IfAvailable);

/// The same sign evaluated only by the exact expansion path (no filter, no
/// shortcut). Exposed so tests can check the filter and shortcut against it.
int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);

/// Exact sign of component `axis` (0 x, 1 y, 2 z) of the cross product
/// (to1 - from1) x (to2 - from2). The symbolic perturbations of the collision
/// predicates reduce to these signs when a determinant is exactly zero.
/// Same contract as orient3d (exact for finite, non-underflowing input).
int cross_product_sign(const Eigen::Vector3d& from1, const Eigen::Vector3d& to1, const Eigen::Vector3d& from2,
                       const Eigen::Vector3d& to2, int axis);

/// The same sign evaluated only by the exact expansion path (no filter, no
/// shortcut). Exposed so tests can check cross_product_sign against it.
int cross_product_sign_exact(const Eigen::Vector3d& from1, const Eigen::Vector3d& to1,
                             const Eigen::Vector3d& from2, const Eigen::Vector3d& to2, int axis);

}  // namespace tcb
