#include "sim/latent/skinned_finger.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/mesh/box_mesh.hpp"

namespace tcb {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d rotation_z(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Vec3::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d rotation_y(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Vec3::UnitY()).toRotationMatrix();
}

/// Flat within 1e-9 of the ramp's ends, so a vertex on a bone's middle plane,
/// exactly at the ramp's end but for the rounding of the joint coordinates,
/// stays rigid (the smoothstep is below 3e-18 there anyway).
double smoothstep(double t) {
  if (t <= 1e-9) return 0.0;
  if (t >= 1.0 - 1e-9) return 1.0;
  return t * t * (3.0 - 2.0 * t);
}

bool finite_range(double lo, double hi) { return std::isfinite(lo) && std::isfinite(hi) && lo < hi; }

}  // namespace

SkinnedFingerDesc finger_preset(const std::string& name) {
  SkinnedFingerDesc desc;
  // Bones 2x as long as the bar is thick, like phalanges: folding two joints
  // cannot press a bone onto its grand-neighbour, so self-collision needs the
  // curl of several joints. The blend spans a whole bone because skinning
  // folds a flexed joint's inner side unless blend > 3 * half-thickness *
  // tan(flex/2) (smoothstep's slope 1.5/w at the joint): 3 cm > 2.25 cm *
  // tan(50 deg) keeps the full flexion range free of inverted tets. The
  // one-sided flexion range [0, 100] deg then makes about a third of uniform
  // codes self-penetrate (measured with the exact oracle, classify_self_points
  // then self_collision_depths, deep > 0: 168 of 500 uniform codes = 33.6 %
  // for both presets, none with an inverted tet; labels cost ~2.4 ms a code
  // for finger_small, ~10 ms for finger_large); flex_max 90 deg gives ~20 %,
  // 110 deg ~55 %. Side bends spread the curl into a helix: the full curl
  // with every side bend at +-20 deg is free.
  desc.size_m = Vec3(0.21, 0.015, 0.015);
  desc.bones = 7;
  desc.flex_min_deg = 0.0;
  desc.flex_max_deg = 100.0;
  desc.side_min_deg = -20.0;
  desc.side_max_deg = 20.0;
  desc.blend_width_m = 0.03;
  if (name == "finger_small") {
    desc.cells = {28, 3, 3};  // 464 vertices, 1512 tets; 4 cells a bone keep each bone's middle plane rigid
    return desc;
  }
  if (name == "finger_large") {
    desc.cells = {42, 5, 5};  // 1548 vertices, 6300 tets
    return desc;
  }
  throw std::invalid_argument("unknown skinned finger preset '" + name +
                              "' (known: finger_small, finger_large)");
}

SkinnedFinger::SkinnedFinger(const SkinnedFingerDesc& desc) : m_desc(desc) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(desc.size_m[a]) || desc.size_m[a] <= 0.0)
      throw std::invalid_argument("skinned finger size must be positive and finite");
  if (desc.cells[0] < 1 || desc.cells[1] < 1 || desc.cells[2] < 1)
    throw std::invalid_argument("skinned finger cells must be at least 1 in each direction");
  if (desc.bones < 2 || desc.bones > desc.cells[0])
    throw std::invalid_argument(
        fmt::format("skinned finger bones must be 2..cells[0] = {}, got {}", desc.cells[0], desc.bones));
  if (!finite_range(desc.flex_min_deg, desc.flex_max_deg))
    throw std::invalid_argument("skinned finger flexion range needs finite flex_min_deg < flex_max_deg");
  if (!finite_range(desc.side_min_deg, desc.side_max_deg))
    throw std::invalid_argument("skinned finger side range needs finite side_min_deg < side_max_deg");

  const int nx = desc.cells[0];
  const double lo_x = -0.5 * desc.size_m.x();
  const double hi_x = 0.5 * desc.size_m.x();
  // Joint j at the first cell column of part j: box_mesh puts cell i into
  // part floor(i*bones/nx), so that column is ceil(j*nx/bones). The same grid
  // formula as box_mesh keeps the joint exactly on a vertex plane.
  m_joint_x_m.assign(static_cast<std::size_t>(desc.bones), 0.0);
  std::vector<double> bone_edges_m = {lo_x};
  for (int j = 1; j < desc.bones; ++j) {
    const int column = static_cast<int>((static_cast<std::int64_t>(j) * nx + desc.bones - 1) / desc.bones);
    m_joint_x_m[static_cast<std::size_t>(j)] =
        lo_x + (hi_x - lo_x) * static_cast<double>(column) / static_cast<double>(nx);
    bone_edges_m.push_back(m_joint_x_m[static_cast<std::size_t>(j)]);
  }
  bone_edges_m.push_back(hi_x);
  double shortest_bone_m = hi_x - lo_x;
  for (std::size_t k = 0; k + 1 < bone_edges_m.size(); ++k)
    shortest_bone_m = std::min(shortest_bone_m, bone_edges_m[k + 1] - bone_edges_m[k]);
  // Wider blends would let two joints' ramps overlap, and a vertex needs
  // three bones then. The slack admits a blend of exactly one bone length
  // despite the rounding of the joint coordinates (its overlap is ~1e-12 of
  // a bone, below anything the weights resolve).
  if (!std::isfinite(desc.blend_width_m) || desc.blend_width_m < 0.0 ||
      desc.blend_width_m > shortest_bone_m * (1.0 + 1e-9))
    throw std::invalid_argument(fmt::format(
        "skinned finger blend_width_m must be in [0, {}] (the shortest bone), got {}", shortest_bone_m,
        desc.blend_width_m));

  m_mesh = std::make_shared<const TetMesh>(
      make_box_mesh(desc.size_m, desc.cells[0], desc.cells[1], desc.cells[2], {desc.bones, 1, 1}));

  m_skin.resize(m_mesh->vertex_count());
  for (std::size_t v = 0; v < m_skin.size(); ++v) {
    const double x = m_mesh->positions_m[v].x();
    int nearest = 1;
    for (int j = 2; j < desc.bones; ++j)
      if (std::abs(x - m_joint_x_m[static_cast<std::size_t>(j)]) <
          std::abs(x - m_joint_x_m[static_cast<std::size_t>(nearest)]))
        nearest = j;
    const double offset_m = x - m_joint_x_m[static_cast<std::size_t>(nearest)];
    double s = 0.0;
    if (desc.blend_width_m > 0.0)
      s = smoothstep(offset_m / desc.blend_width_m + 0.5);
    else
      s = offset_m >= 0.0 ? 1.0 : 0.0;
    Skin& skin = m_skin[v];
    // One bone when the ramp is flat: keeps rigid vertices exactly rigid.
    if (s == 0.0) {
      skin = {nearest - 1, nearest - 1, 0.0};
    } else if (s == 1.0) {
      skin = {nearest, nearest, 0.0};
    } else {
      skin = {nearest - 1, nearest, s};
    }
  }
}

void SkinnedFinger::check_code(const Eigen::VectorXd& z) const {
  if (z.size() != latent_size())
    throw std::invalid_argument(
        fmt::format("skinned finger code has {} entries, expected {}", z.size(), latent_size()));
}

std::vector<double> SkinnedFinger::joint_angles_rad(const Eigen::VectorXd& z) const {
  check_code(z);
  std::vector<double> angles(static_cast<std::size_t>(z.size()));
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const bool flex = i % 2 == 0;
    const double lo = flex ? m_desc.flex_min_deg : m_desc.side_min_deg;
    const double hi = flex ? m_desc.flex_max_deg : m_desc.side_max_deg;
    angles[static_cast<std::size_t>(i)] = (lo + 0.5 * (z[i] + 1.0) * (hi - lo)) * kRadPerDeg;
  }
  return angles;
}

SkinnedFinger::Pose SkinnedFinger::pose(const std::vector<double>& angles_rad) const {
  Pose p;
  p.rotation.assign(static_cast<std::size_t>(m_desc.bones), Eigen::Matrix3d::Identity());
  p.translation_m.assign(static_cast<std::size_t>(m_desc.bones), Vec3::Zero());
  for (int k = 1; k < m_desc.bones; ++k) {
    const auto j = static_cast<std::size_t>(k);
    const Eigen::Matrix3d joint_rotation =
        rotation_z(-angles_rad[2 * (j - 1)]) * rotation_y(angles_rad[2 * (j - 1) + 1]);
    const Vec3 joint_m(m_joint_x_m[j], 0.0, 0.0);
    // G_k(x) = G_{k-1}(p + R (x - p)).
    p.rotation[j] = p.rotation[j - 1] * joint_rotation;
    p.translation_m[j] = p.rotation[j - 1] * (joint_m - joint_rotation * joint_m) + p.translation_m[j - 1];
  }
  return p;
}

std::vector<Vec3> SkinnedFinger::decode(const Eigen::VectorXd& z) const {
  const Pose p = pose(joint_angles_rad(z));
  const auto& rest = m_mesh->positions_m;
  std::vector<Vec3> x(rest.size());
  for (std::size_t v = 0; v < rest.size(); ++v) {
    const Skin& s = m_skin[v];
    const auto a = static_cast<std::size_t>(s.proximal_bone);
    const auto b = static_cast<std::size_t>(s.distal_bone);
    const Vec3 xa = p.rotation[a] * rest[v] + p.translation_m[a];
    if (a == b) {
      x[v] = xa;
    } else {
      const Vec3 xb = p.rotation[b] * rest[v] + p.translation_m[b];
      x[v] = (1.0 - s.distal_weight) * xa + s.distal_weight * xb;
    }
  }
  return x;
}

Eigen::MatrixXd SkinnedFinger::jacobian(const Eigen::VectorXd& z) const {
  const std::vector<double> angles = joint_angles_rad(z);
  const Pose p = pose(angles);
  const auto& rest = m_mesh->positions_m;
  const int joints = m_desc.bones - 1;
  const double flex_rad_per_z = 0.5 * (m_desc.flex_max_deg - m_desc.flex_min_deg) * kRadPerDeg;
  const double side_rad_per_z = 0.5 * (m_desc.side_max_deg - m_desc.side_min_deg) * kRadPerDeg;

  // Joint j turns every bone k >= j rigidly about the world point
  // P_j = G_{j-1}(p_j) with world angular velocity omega, so
  // d G_k(x)/d angle = omega x (G_k(x) - P_j). For R_j = R_z(-f) R_y(s):
  // dR/df = [-e_z]x R_j and dR/ds = [R_z(-f) e_y]x R_j, mapped to the world
  // by the parent rotation A_{j-1}.
  std::vector<Vec3> pivot_m(static_cast<std::size_t>(m_desc.bones));
  std::vector<Vec3> omega_flex(static_cast<std::size_t>(m_desc.bones));
  std::vector<Vec3> omega_side(static_cast<std::size_t>(m_desc.bones));
  for (int j = 1; j <= joints; ++j) {
    const auto u = static_cast<std::size_t>(j);
    const Eigen::Matrix3d& parent = p.rotation[u - 1];
    pivot_m[u] = parent * Vec3(m_joint_x_m[u], 0.0, 0.0) + p.translation_m[u - 1];
    omega_flex[u] = -(parent * Vec3::UnitZ()) * flex_rad_per_z;
    omega_side[u] = parent * (rotation_z(-angles[2 * (u - 1)]) * Vec3::UnitY()) * side_rad_per_z;
  }

  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(3 * rest.size()), latent_size());
  for (std::size_t v = 0; v < rest.size(); ++v) {
    const Skin& s = m_skin[v];
    const int bones[2] = {s.proximal_bone, s.distal_bone};
    const double weights[2] = {s.proximal_bone == s.distal_bone ? 1.0 : 1.0 - s.distal_weight,
                               s.proximal_bone == s.distal_bone ? 0.0 : s.distal_weight};
    const auto row = static_cast<Eigen::Index>(3 * v);
    for (int t = 0; t < 2; ++t) {
      if (weights[t] == 0.0) continue;
      const auto k = static_cast<std::size_t>(bones[t]);
      const Vec3 posed = p.rotation[k] * rest[v] + p.translation_m[k];
      for (int j = 1; j <= bones[t]; ++j) {
        const auto u = static_cast<std::size_t>(j);
        const Vec3 arm = posed - pivot_m[u];
        jac.block<3, 1>(row, 2 * (j - 1)) += weights[t] * omega_flex[u].cross(arm);
        jac.block<3, 1>(row, 2 * (j - 1) + 1) += weights[t] * omega_side[u].cross(arm);
      }
    }
  }
  return jac;
}

Eigen::VectorXd SkinnedFinger::rest_code() const {
  Eigen::VectorXd z(latent_size());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const bool flex = i % 2 == 0;
    const double lo = flex ? m_desc.flex_min_deg : m_desc.side_min_deg;
    const double hi = flex ? m_desc.flex_max_deg : m_desc.side_max_deg;
    z[i] = 2.0 * (0.0 - lo) / (hi - lo) - 1.0;
  }
  return z;
}

Eigen::VectorXd SkinnedFinger::full_curl_code() const {
  Eigen::VectorXd z = rest_code();
  for (Eigen::Index i = 0; i < z.size(); i += 2) z[i] = 1.0;
  return z;
}

}  // namespace tcb
