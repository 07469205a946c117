#pragma once
/// A small multilayer perceptron written on Eigen: the neural collision
/// detector of seed 002 (N-Penetrate), which maps a latent code z to one
/// logit r (self-colliding when sigmoid(r) > 0.5, i.e. r > 0).
///
/// Why hand-written (docs/architecture.md): libtorch costs 162 Debian
/// packages, compiles three times slower, and spends ~200 us on one forward
/// and input-gradient call that takes a few microseconds here; this MLP is
/// also bit-reproducible (no threads, no BLAS reductions in varying order).
///
/// Contract:
/// - layers {n0, n1, ..., nk}: hidden layers apply the activation (tanh, or
///   CELU with alpha = 1: x > 0 ? x : exp(x) - 1; both smooth, as the seed
///   asks, so the ALM gets a continuous gradient); the last layer is linear;
/// - initial weights: Glorot-uniform from counter_random (seed, layer,
///   index), biases 0: the same seed gives the same initial network on any
///   machine; training (tanh, exp) is bit-reproducible for one build and math
///   library, across machines only as far as their tanh and exp agree;
/// - flat parameter order: layer by layer, each W (n_{l+1} x n_l) in
///   column-major order, then its bias;
/// - batches are matrices whose columns are samples;
/// - save/load: JSON ("format": "tcbench-mlp-1"), parameters as doubles
///   printed to round-trip, so a loaded network's outputs are bit-identical.
/// Templated on the scalar: tests check gradients in double.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "sim/io/atomic_file.hpp"
#include "sim/random/counter_random.hpp"

namespace tcb::neural {

enum class Activation { Tanh, Celu };

inline const char* activation_name(Activation a) { return a == Activation::Tanh ? "tanh" : "celu"; }

template <class Scalar>
class Mlp {
 public:
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  Mlp() = default;
  Mlp(std::vector<int> layer_sizes, Activation hidden, std::uint64_t seed)
      : m_sizes(std::move(layer_sizes)), m_activation(hidden) {
    if (m_sizes.size() < 2) throw std::invalid_argument("Mlp: needs at least an input and an output layer");
    for (const int n : m_sizes)
      if (n <= 0) throw std::invalid_argument("Mlp: layer sizes must be positive");
    for (std::size_t l = 0; l + 1 < m_sizes.size(); ++l) {
      const int in = m_sizes[l], out = m_sizes[l + 1];
      const double limit = std::sqrt(6.0 / (in + out));
      Mat w(out, in);
      for (int j = 0; j < in; ++j)
        for (int i = 0; i < out; ++i)
          w(i, j) = static_cast<Scalar>(limit * uniform_pm1(seed, l, static_cast<std::uint64_t>(j) * out + i));
      m_weights.push_back(std::move(w));
      m_biases.push_back(Vec::Zero(out));
    }
  }

  int input_size() const { return m_sizes.front(); }
  int output_size() const { return m_sizes.back(); }
  const std::vector<int>& layer_sizes() const { return m_sizes; }
  Activation activation() const { return m_activation; }
  std::size_t parameter_count() const {
    std::size_t n = 0;
    for (std::size_t l = 0; l < m_weights.size(); ++l) n += static_cast<std::size_t>(m_weights[l].size() + m_biases[l].size());
    return n;
  }

  Vec parameters() const {
    Vec p(static_cast<Eigen::Index>(parameter_count()));
    Eigen::Index at = 0;
    for (std::size_t l = 0; l < m_weights.size(); ++l) {
      p.segment(at, m_weights[l].size()) = m_weights[l].reshaped();
      at += m_weights[l].size();
      p.segment(at, m_biases[l].size()) = m_biases[l];
      at += m_biases[l].size();
    }
    return p;
  }
  void set_parameters(const Vec& p) {
    if (static_cast<std::size_t>(p.size()) != parameter_count())
      throw std::invalid_argument("Mlp::set_parameters: wrong parameter count");
    Eigen::Index at = 0;
    for (std::size_t l = 0; l < m_weights.size(); ++l) {
      m_weights[l].reshaped() = p.segment(at, m_weights[l].size());
      at += m_weights[l].size();
      m_biases[l] = p.segment(at, m_biases[l].size());
      at += m_biases[l].size();
    }
  }

  Vec forward(const Vec& z) const {
    check_input(z.size());
    Vec a = z;
    for (std::size_t l = 0; l < m_weights.size(); ++l) {
      Vec h = m_weights[l] * a + m_biases[l];
      a = l + 1 < m_weights.size() ? activate(h) : h;
    }
    return a;
  }

  Mat forward_batch(const Mat& z) const {
    check_input(z.rows());
    Mat a = z;
    for (std::size_t l = 0; l < m_weights.size(); ++l) {
      Mat h = (m_weights[l] * a).colwise() + m_biases[l];
      a = l + 1 < m_weights.size() ? activate(h) : h;
    }
    return a;
  }

  /// r(z) and dr/dz; the network must have one output.
  Scalar value_and_input_gradient(const Vec& z, Vec& grad_z) const {
    check_input(z.size());
    if (output_size() != 1) throw std::invalid_argument("Mlp: the input gradient needs one output");
    std::vector<Vec> act(m_weights.size() + 1);
    act[0] = z;
    for (std::size_t l = 0; l < m_weights.size(); ++l) {
      Vec h = m_weights[l] * act[l] + m_biases[l];
      act[l + 1] = l + 1 < m_weights.size() ? activate(h) : h;
    }
    Vec delta = Vec::Ones(1);
    for (std::size_t l = m_weights.size(); l-- > 0;) {
      delta = m_weights[l].transpose() * delta;
      if (l > 0) delta = delta.cwiseProduct(derivative_at(act[l]));
    }
    grad_z = std::move(delta);
    return act.back()[0];
  }

  /// dL/dtheta (flat order) for a batch z, given dL/d(output) (outputs x samples).
  Vec parameter_gradient(const Mat& z, const Mat& dloss_dout) const {
    return gradient_through(z, [&](const Mat&) { return dloss_dout; });
  }

  /// One forward pass and one backward pass: `dloss(output)` (outputs x
  /// samples) returns dL/d(output) from the batch's outputs; returns dL/dtheta.
  /// Training calls this rather than forward_batch then parameter_gradient,
  /// which would run the forward pass (and its tanh) twice.
  template <class DLoss>
  Vec gradient_through(const Mat& z, DLoss&& dloss) const {
    check_input(z.rows());
    std::vector<Mat> act(m_weights.size());
    act[0] = z;
    for (std::size_t l = 0; l + 1 < m_weights.size(); ++l) act[l + 1] = activate(Mat((m_weights[l] * act[l]).colwise() + m_biases[l]));
    const Mat out = (m_weights.back() * act.back()).colwise() + m_biases.back();
    const Mat dloss_dout = dloss(out);
    if (dloss_dout.rows() != output_size() || dloss_dout.cols() != z.cols())
      throw std::invalid_argument("Mlp::parameter_gradient: dloss_dout has the wrong shape");
    Vec grad(static_cast<Eigen::Index>(parameter_count()));
    Eigen::Index at = grad.size();
    Mat delta = dloss_dout;
    for (std::size_t l = m_weights.size(); l-- > 0;) {
      at -= m_biases[l].size();
      grad.segment(at, m_biases[l].size()) = delta.rowwise().sum();
      at -= m_weights[l].size();
      const Mat dw = delta * act[l].transpose();
      grad.segment(at, m_weights[l].size()) = dw.reshaped();
      if (l > 0) delta = (m_weights[l].transpose() * delta).cwiseProduct(derivative_at(act[l]));
    }
    return grad;
  }

  nlohmann::ordered_json to_json() const {
    nlohmann::ordered_json j;
    j["format"] = "tcbench-mlp-1";
    j["activation"] = activation_name(m_activation);
    j["layers"] = m_sizes;
    std::vector<double> p;
    const Vec params = parameters();
    for (Eigen::Index i = 0; i < params.size(); ++i) p.push_back(static_cast<double>(params[i]));
    j["parameters"] = p;
    return j;
  }

  /// Throws std::invalid_argument saying what is wrong.
  static Mlp from_json(const nlohmann::ordered_json& j) {
    if (!j.is_object() || j.value("format", std::string()) != "tcbench-mlp-1")
      throw std::invalid_argument("not a tcbench-mlp-1 network (\"format\" missing or different)");
    const std::string act = j.value("activation", std::string());
    if (act != "tanh" && act != "celu") throw std::invalid_argument("activation must be tanh or celu, not '" + act + "'");
    if (!j.contains("layers") || !j["layers"].is_array()) throw std::invalid_argument("\"layers\" must be an array");
    std::vector<int> sizes;
    for (const auto& n : j["layers"]) {
      if (!n.is_number_integer() || n.get<std::int64_t>() < 1 || n.get<std::int64_t>() > 1000000)
        throw std::invalid_argument("\"layers\" must hold integers in [1, 1000000]");
      sizes.push_back(n.get<int>());
    }
    if (sizes.size() < 2 || sizes.size() > 1000)
      throw std::invalid_argument("\"layers\" needs 2 to 1000 sizes (input, hidden..., output)");
    // The count the sizes imply, checked against the file before anything is
    // allocated: a header claiming huge layers in a short file is refused, not
    // allocated (each term is below 10^12 and there are fewer than 1000: no overflow).
    std::uint64_t implied = 0;
    for (std::size_t l = 0; l + 1 < sizes.size(); ++l)
      implied += static_cast<std::uint64_t>(sizes[l]) * static_cast<std::uint64_t>(sizes[l + 1]) +
                 static_cast<std::uint64_t>(sizes[l + 1]);
    if (!j.contains("parameters") || !j["parameters"].is_array() || j["parameters"].size() != implied)
      throw std::invalid_argument("\"parameters\" must be an array of " + std::to_string(implied) + " numbers");
    Mlp net(sizes, act == "tanh" ? Activation::Tanh : Activation::Celu, 0);
    if (j["parameters"].size() != net.parameter_count())
      throw std::invalid_argument("\"parameters\" must be an array of " + std::to_string(net.parameter_count()) + " numbers");
    Vec p(static_cast<Eigen::Index>(net.parameter_count()));
    Eigen::Index i = 0;
    for (const auto& x : j["parameters"]) {
      if (!x.is_number()) throw std::invalid_argument("\"parameters\" must hold numbers");
      p[i++] = static_cast<Scalar>(x.get<double>());
    }
    net.set_parameters(p);
    return net;
  }

  /// Written to a temporary name and renamed (sim/io/atomic_file.hpp).
  void save(const std::string& path) const { write_file_atomically(path, to_json().dump() + "\n"); }

  /// Throws std::runtime_error naming the file and the problem.
  static Mlp load(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    try {
      return from_json(nlohmann::ordered_json::parse(in));
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
  }

 private:
  void check_input(Eigen::Index n) const {
    if (n != input_size())
      throw std::invalid_argument("Mlp: input of size " + std::to_string(n) + ", expected " + std::to_string(input_size()));
  }
  template <class M>
  M activate(const M& h) const {
    if (m_activation == Activation::Tanh) return h.array().tanh().matrix();
    return h.unaryExpr([](Scalar x) { return x > Scalar(0) ? x : std::expm1(x); });
  }
  // The activation's derivative from its value a = act(h): tanh' = 1 - a^2;
  // CELU' = 1 for h > 0 (a > 0), exp(h) = a + 1 otherwise.
  template <class M>
  M derivative_at(const M& a) const {
    if (m_activation == Activation::Tanh) return (Scalar(1) - a.array().square()).matrix();
    return a.unaryExpr([](Scalar x) { return x > Scalar(0) ? Scalar(1) : x + Scalar(1); });
  }

  std::vector<int> m_sizes;
  Activation m_activation = Activation::Tanh;
  std::vector<Mat> m_weights;
  std::vector<Vec> m_biases;
};

}  // namespace tcb::neural
