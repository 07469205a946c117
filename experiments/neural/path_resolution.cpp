#include "experiments/neural/path_resolution.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "experiments/metrics/distribution.hpp"
#include "experiments/neural/finger_labeller.hpp"
#include "method/neural/model_file.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"
#include "sim/latent/latent_path.hpp"

namespace tcb {

PathResolution resolve_path(const PathResolutionSettings& s) {
  const auto finger = std::make_unique<SkinnedFinger>(finger_preset_option(s.preset));
  neural::ModelFile model = neural::read_model_file(s.model);
  const neural::Mlp<double>& net = model.net;
  if (net.input_size() != finger->latent_size() || net.output_size() != 1)
    throw InputError(s.model.string(), 0,
                     fmt::format("the network takes {} inputs and gives {} outputs; {} needs {} inputs and one logit",
                                 net.input_size(), net.output_size(), s.preset, finger->latent_size()));
  if (!model.preset().empty() && model.preset() != s.preset)
    throw InputError(s.model.string(), 0,
                     fmt::format("the network was trained for {}, not {} (--preset)", model.preset(), s.preset));
  const LatentPath path = read_latent_path_csv(s.path, finger->latent_size());
  FingerLabeller labeller(*finger);
  const neural::Constraint constraint = [&](const Eigen::VectorXd& z, Eigen::VectorXd& grad) {
    return net.value_and_input_gradient(z, grad) + s.margin;
  };
  PathResolution out;
  std::vector<double> distances;
  std::ostringstream csv;
  csv << "time_s,logit,network_collides,oracle_collides,oracle_pd_m,alm_steps,alm_evaluations,alm_feasible,"
         "alm_converged,distance,resolved\n";
  for (std::size_t i = 0; i < path.code.size(); ++i) {
    const Eigen::VectorXd& z0 = path.code[i];
    const double logit = net.forward(z0)[0];
    const SelfPenetration truth = labeller.penetration(z0);
    const bool says = logit > 0.0;
    ++out.frames;
    out.network_colliding += says;
    out.oracle_colliding += truth.penetrates;
    out.true_positives += says && truth.penetrates;
    csv << fmt::format("{},{},{},{},{}", path.time_s[i], logit, int(says), int(truth.penetrates), truth.pd_m);
    if (!says) {
      csv << ",,,,,,\n";
      continue;
    }
    neural::AlmState state = neural::alm_start(z0, s.alm);
    std::int64_t steps = 0;
    bool done = false;
    while (!done && steps < s.max_steps) {
      Budget budget = s.work_per_step > 0 ? Budget::work_units(s.work_per_step) : Budget::unlimited();
      done = neural::alm_resume(state, constraint, s.alm, budget);
      ++steps;
    }
    const double distance = (state.z - z0).norm();
    const bool resolved = done && !labeller.penetration(state.z).penetrates;
    out.resolved += resolved;
    out.abandoned += !done;
    out.steps_max = std::max(out.steps_max, steps);
    distances.push_back(distance);
    csv << fmt::format(",{},{},{},{},{},{}\n", steps, state.evaluations,
                       int(state.c <= s.alm.feasibility_tolerance), int(state.converged), distance, int(resolved));
  }
  out.distance_median = distances.empty() ? std::nan("") : summarize(distances).p50;
  write_file_atomically(s.out, csv.str());
  return out;
}

}  // namespace tcb
