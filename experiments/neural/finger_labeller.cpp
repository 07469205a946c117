#include "experiments/neural/finger_labeller.hpp"

#include <stdexcept>

#include "sim/io/input_error.hpp"

namespace tcb {

SkinnedFingerDesc finger_preset_option(const std::string& name) {
  try {
    return finger_preset(name);
  } catch (const std::invalid_argument& e) {
    throw InputError("--preset", 0, e.what());
  }
}

FingerLabeller::FingerLabeller(const SkinnedFinger& finger) : m_finger(&finger) {
  m_body.name = "finger";
  m_body.mesh = finger.mesh();
  m_body.passive = true;
  m_body.self_collision = true;
}

SelfPenetration FingerLabeller::penetration(const Eigen::VectorXd& z) {
  const auto start = std::chrono::steady_clock::now();
  m_body.x_m = m_finger->decode(z);
  SelfPenetration p = self_penetration(m_body);
  m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++m_labels;
  return p;
}

neural::Label FingerLabeller::operator()(const Eigen::VectorXd& z) {
  const SelfPenetration p = penetration(z);
  return {p.penetrates, p.pd_m};
}

}  // namespace tcb
