#include "method/neural/neural_handler.hpp"

#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "method/handler/work_units.hpp"
#include "method/neural/model_file.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

void NeuralHandler::init(const World& world, const CollisionSettings&) {
  m_networks.assign(world.bodies.size(), std::nullopt);
  m_verdicts.assign(world.bodies.size(), 0);
  m_logits.assign(world.bodies.size(), std::numeric_limits<double>::quiet_NaN());
  bool any = false;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const Body& body = world.bodies[b];
    if (!body.latent) continue;
    any = true;
    const std::string who = "object '" + body.name + "'";
    if (body.latent->model_path.empty())
      throw InputError("--method neural", 0, who + " names no latent_model: the neural method needs the network "
                                             "trained for its family (tcbench neural train)");
    const std::string path = body.latent->model_path.string();
    neural::ModelFile model = neural::read_model_file(body.latent->model_path);
    const int n = body.latent->finger->latent_size();
    if (model.net.input_size() != n || model.net.output_size() != 1)
      throw InputError(path, 0, fmt::format("the network takes {} inputs and gives {} outputs; {} (family {}) needs {} "
                                            "inputs and one logit",
                                            model.net.input_size(), model.net.output_size(), who, body.latent->family, n));
    // Both fingers have 12 latent entries: only the file's record tells a
    // network trained on the other mesh apart.
    if (!model.preset().empty() && model.preset() != body.latent->family)
      throw InputError(path, 0, fmt::format("the network was trained for {}, but {} is a {}", model.preset(), who,
                                            body.latent->family));
    m_networks[b] = std::move(model.net);
  }
  if (!any)
    throw InputError("--method neural", 0, "judges only latent-driven objects (a scene object with latent_path); "
                                           "this scene has none");
}

StepReport NeuralHandler::step(World& world, Budget& budget) {
  StepReport report;
  for (std::size_t b = 0; b < m_networks.size(); ++b) {
    if (!m_networks[b] || budget.expired()) continue;
    budget.charge(work::kNetworkEvaluation);
    report.work_units += work::kNetworkEvaluation;
    m_logits[b] = m_networks[b]->forward(world.bodies[b].latent_code)[0];
    m_verdicts[b] = m_logits[b] > 0.0;
  }
  for (const char v : m_verdicts) report.colliding_points += v;
  return report;
}

}  // namespace tcb
