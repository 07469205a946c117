#pragma once
/// Adam (Kingma and Ba 2015) on a flat parameter vector: bias-corrected
/// first and second moments. Deterministic: plain element-wise arithmetic.

#include <cmath>
#include <cstdint>

#include <Eigen/Dense>

namespace tcb::neural {

template <class Scalar>
class Adam {
 public:
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  explicit Adam(Scalar learning_rate, Scalar beta1 = Scalar(0.9), Scalar beta2 = Scalar(0.999), Scalar epsilon = Scalar(1e-8))
      : m_rate(learning_rate), m_beta1(beta1), m_beta2(beta2), m_epsilon(epsilon) {}

  /// One step against `gradient` (same size as params at every call).
  void step(Vec& params, const Vec& gradient) {
    if (m_m.size() != params.size())
      m_m = Vec::Zero(params.size()), m_v = Vec::Zero(params.size()), m_t = 0, m_beta1_t = m_beta2_t = Scalar(1);
    ++m_t;
    // beta^t as running products, not std::pow: plain multiplications round
    // the same under every math library, so weights match across machines.
    m_beta1_t *= m_beta1;
    m_beta2_t *= m_beta2;
    m_m = m_beta1 * m_m + (Scalar(1) - m_beta1) * gradient;
    m_v = m_beta2 * m_v + (Scalar(1) - m_beta2) * gradient.cwiseProduct(gradient);
    const Scalar c1 = Scalar(1) - m_beta1_t;
    const Scalar c2 = Scalar(1) - m_beta2_t;
    params.array() -= m_rate * (m_m.array() / c1) / ((m_v.array() / c2).sqrt() + m_epsilon);
  }

  std::int64_t steps() const { return m_t; }

 private:
  Scalar m_rate, m_beta1, m_beta2, m_epsilon;
  Vec m_m, m_v;
  std::int64_t m_t = 0;
  Scalar m_beta1_t = Scalar(1), m_beta2_t = Scalar(1);
};

}  // namespace tcb::neural
