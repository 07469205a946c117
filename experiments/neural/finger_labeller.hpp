#pragma once
/// Exact labels for the skinned finger's codes: decode z, then ask the
/// oracle whether the mesh penetrates itself (oracle/self_penetration.hpp).
/// This is where the oracle is handed to the neural code (method/neural never
/// includes oracle/). Labelling time is counted here, apart from training.

#include <chrono>
#include <memory>

#include "method/neural/active_learning.hpp"
#include "oracle/self_penetration.hpp"
#include "sim/latent/skinned_finger.hpp"
#include "sim/world/world.hpp"

namespace tcb {

/// finger_preset(name) for a preset a user named: InputError naming --preset
/// (and listing the presets) for an unknown one.
SkinnedFingerDesc finger_preset_option(const std::string& name);

class FingerLabeller {
 public:
  explicit FingerLabeller(const SkinnedFinger& finger);
  /// The self-penetration of decode(z).
  SelfPenetration penetration(const Eigen::VectorXd& z);
  /// penetration(z) as a training label (depth = pd_m).
  neural::Label operator()(const Eigen::VectorXd& z);
  /// Labels made so far, and the wall time they took (decode + oracle).
  std::int64_t labels() const { return m_labels; }
  double seconds() const { return m_seconds; }

 private:
  const SkinnedFinger* m_finger;
  Body m_body;
  std::int64_t m_labels = 0;
  double m_seconds = 0.0;
};

}  // namespace tcb
