// The neural detector's costs (seed 002), side by side in one run: one
// evaluation with its input gradient (what a step of a neural handler and
// every ALM iteration pay, whatever the mesh size), a training step, and the
// decoder it stands beside (D(z) and dD/dz of the skinned finger).
//   build/release/experiments/micro/micro_neural_detector --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "method/neural/active_learning.hpp"
#include "method/neural/losses.hpp"
#include "sim/latent/skinned_finger.hpp"

namespace {

using namespace tcb;
using namespace tcb::neural;

const std::vector<int> kLayers = {12, 64, 64, 64, 1};

void evaluate(benchmark::State& state, Activation activation) {
  const Mlp<double> net(kLayers, activation, 1);
  Eigen::VectorXd grad;
  std::uint64_t i = 0;
  for (auto _ : state) {
    const Eigen::VectorXd z = uniform_code(12, 7, 0, i++ % 1024);
    benchmark::DoNotOptimize(net.value_and_input_gradient(z, grad));
  }
}
void BM_evaluate_tanh(benchmark::State& state) { evaluate(state, Activation::Tanh); }
void BM_evaluate_celu(benchmark::State& state) { evaluate(state, Activation::Celu); }

// One Adam step on a minibatch: forward, cross-entropy, backprop.
void BM_train_step(benchmark::State& state) {
  const auto batch = static_cast<Eigen::Index>(state.range(0));
  Mlp<double> net(kLayers, Activation::Tanh, 1);
  Adam<double> adam(1e-3);
  Eigen::MatrixXd z(12, batch);
  Eigen::VectorXd label(batch), d;
  for (Eigen::Index c = 0; c < batch; ++c) {
    z.col(c) = uniform_code(12, 3, 0, static_cast<std::uint64_t>(c));
    label[c] = z.col(c).sum() > 0.0 ? 1.0 : 0.0;
  }
  Eigen::VectorXd p = net.parameters();
  for (auto _ : state) {
    adam.step(p, net.gradient_through(z, [&](const Eigen::MatrixXd& out) {
      cross_entropy(Eigen::VectorXd(out.row(0).transpose()), label, d);
      return Eigen::MatrixXd(d.transpose());
    }));
    net.set_parameters(p);
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(batch), benchmark::Counter::kIsIterationInvariantRate);
}

void decode(benchmark::State& state, const char* preset, bool jacobian) {
  const SkinnedFinger finger(finger_preset(preset));
  std::uint64_t i = 0;
  for (auto _ : state) {
    const Eigen::VectorXd z = uniform_code(finger.latent_size(), 5, 0, i++ % 1024);
    if (jacobian)
      benchmark::DoNotOptimize(finger.jacobian(z).data());
    else
      benchmark::DoNotOptimize(finger.decode(z).data());
  }
  state.counters["vertices"] = static_cast<double>(finger.mesh()->vertex_count());
}
void BM_decode_small(benchmark::State& state) { decode(state, "finger_small", false); }
void BM_decode_large(benchmark::State& state) { decode(state, "finger_large", false); }
void BM_jacobian_small(benchmark::State& state) { decode(state, "finger_small", true); }
void BM_jacobian_large(benchmark::State& state) { decode(state, "finger_large", true); }

}  // namespace

BENCHMARK(BM_evaluate_tanh);
BENCHMARK(BM_evaluate_celu);
BENCHMARK(BM_train_step)->Arg(128)->Arg(256);
BENCHMARK(BM_decode_small);
BENCHMARK(BM_decode_large);
BENCHMARK(BM_jacobian_small);
BENCHMARK(BM_jacobian_large);
BENCHMARK_MAIN();
