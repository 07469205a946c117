#pragma once
/// A latent family of self-colliding tet meshes for the neural self-collision
/// detector (seed 002, METHOD.md section 8): an articulated, skinned,
/// finger-like bar whose positions D(z) and Jacobian dD/dz are analytic.
///
/// Contract:
/// - Rest mesh: make_box_mesh(size, cells, {bones, 1, 1}), centred on the
///   origin, tet_part = bone index 0..bones-1 along +x. Bone 0 (x min) is the
///   base and is fixed; joint j (1..bones-1) sits at the boundary between
///   bones j-1 and j, on the centre line (y = z = 0 at rest).
/// - Each joint has two angles: flexion f (curls the distal bar towards -y,
///   i.e. a rotation by -f about +z; ranges are one-sided, f >= 0 curls) and
///   side bend s (a rotation by s about +y). The joint rotation is
///   R_j = R_z(-f_j) * R_y(s_j) about the joint's rest point p_j: the side bend
///   acts first in the joint's own frame, then the flexion. Bone k's rigid map
///   is G_k = T_1 o T_2 o ... o T_k with T_j(x) = p_j + R_j (x - p_j) (the
///   proximal joints move the distal ones); G_0 = identity.
/// - Latent: z has 2*(bones-1) entries (f_1, s_1, f_2, s_2, ...); angle =
///   lo + (z+1)/2 * (hi-lo) with [lo, hi] the desc's range in degrees. z outside
///   [-1, 1] extrapolates that map linearly (optimisers may step outside).
/// - Skinning: linear blend skinning. A vertex at rest x is weighted between the
///   two bones meeting at the joint nearest to x: weight s on the distal bone
///   and 1-s on the proximal one, s = smoothstep over [x_j - w/2, x_j + w/2]
///   (w = blend_width_m; w = 0 gives rigid bones, a vertex exactly on a joint
///   then going to the distal bone). Since w is at most the shortest bone, the
///   weights are continuous in x and sum to 1.
/// - Units: metres for positions and sizes, degrees in the desc, radians from
///   joint_angles_rad().
/// - Rest orientation: all rest tets are positive (box mesh). Skinning folds a
///   flexed joint's inner side, inverting tets, once flexion f exceeds
///   2 atan(w / (3 h)) (h = half the bar's thickness along y); the presets keep
///   their whole range below that.
/// Cost: decode O(V * bones) after O(bones) kinematics; jacobian O(V * latent).

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

/// The family's parameters. flex/side ranges in degrees, lo < hi each.
struct SkinnedFingerDesc {
  Vec3 size_m = Vec3(0.21, 0.015, 0.015);  ///< bar extents; x is the chain axis
  std::array<int, 3> cells = {28, 3, 3};    ///< box cells; cells[0] >= bones
  int bones = 7;                            ///< >= 2; bone 0 is the fixed base
  double flex_min_deg = 0.0;
  double flex_max_deg = 100.0;
  double side_min_deg = -20.0;
  double side_max_deg = 20.0;
  double blend_width_m = 0.03;              ///< in [0, shortest bone length]
};

/// Named presets, both a 21 x 1.5 x 1.5 cm bar of 7 bones, flexion [0, 100]
/// deg, side bend +-20 deg, blend 3 cm (one bone): "finger_small" (464
/// vertices) and "finger_large" (1548 vertices). Throws std::invalid_argument naming the known presets
/// for any other name.
SkinnedFingerDesc finger_preset(const std::string& name);

/// The articulated bar: rest mesh plus the analytic decoder z -> positions.
class SkinnedFinger {
 public:
  /// Builds the rest mesh and skinning weights; throws std::invalid_argument
  /// on a bad desc (non-positive or non-finite size, cells < 1, bones < 2 or
  /// > cells[0], a range with lo >= hi or non-finite, blend width outside
  /// [0, shortest bone]).
  explicit SkinnedFinger(const SkinnedFingerDesc& desc);

  /// The rest mesh; tet_part = bone index.
  std::shared_ptr<const TetMesh> mesh() const { return m_mesh; }
  /// 2 * (bones - 1).
  int latent_size() const { return 2 * (m_desc.bones - 1); }
  const SkinnedFingerDesc& desc() const { return m_desc; }

  /// The joint angles (radians) of z, in z's order (f_1, s_1, f_2, ...).
  /// Throws std::invalid_argument when z.size() != latent_size().
  std::vector<double> joint_angles_rad(const Eigen::VectorXd& z) const;
  /// D(z): the skinned vertex positions (metres). Throws as above.
  std::vector<Vec3> decode(const Eigen::VectorXd& z) const;
  /// dD/dz, (3V) x latent_size, analytic: row 3*v+k is d x_v[k] / dz.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& z) const;

  /// The code whose angles are all 0: decode gives the rest positions. With a
  /// one-sided flexion range [0, hi] its flexion entries are -1; an entry lies
  /// outside [-1, 1] when 0 is outside its range.
  Eigen::VectorXd rest_code() const;
  /// Every flexion at its maximum (z = 1), side bends at 0 angle; the presets'
  /// full curl penetrates itself.
  Eigen::VectorXd full_curl_code() const;

  /// Per vertex, the two bones it is skinned to and the distal bone's weight
  /// (the proximal one has 1 - weight); both bones equal when rigid.
  struct Skin {
    int proximal_bone = 0;
    int distal_bone = 0;
    double distal_weight = 0.0;
  };
  const std::vector<Skin>& skin() const { return m_skin; }

 private:
  /// Per bone k, its rigid map G_k(x) = rotation * x + translation.
  struct Pose {
    std::vector<Eigen::Matrix3d> rotation;
    std::vector<Vec3> translation_m;
  };
  void check_code(const Eigen::VectorXd& z) const;
  Pose pose(const std::vector<double>& angles_rad) const;

  SkinnedFingerDesc m_desc;
  std::shared_ptr<const TetMesh> m_mesh;
  std::vector<double> m_joint_x_m;  ///< index j = 1..bones-1 (entry 0 unused)
  std::vector<Skin> m_skin;
};

}  // namespace tcb
