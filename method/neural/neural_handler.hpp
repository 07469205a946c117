#pragma once
/// `neural`: seed 002's learned self-collision detector as a collision
/// handling method. For each latent-driven body (sim/latent/latent_path.hpp)
/// it evaluates the network trained for the body's family (the scene's
/// latent_model, written by `tcbench neural train`) at the body's current
/// latent code: self-colliding when the logit is > 0 (sigmoid > 0.5). One
/// forward pass per body per step, a cost independent of the mesh size; no
/// positions are read.
///
/// What it reports: a whole-body verdict (self_collision_verdicts()), no
/// points: contacts() stays empty and reports_points() is false, so the
/// run's point-level recall and precision are not measured for it; the
/// oracle judges its verdict per frame (summary `self_frames`). It applies no
/// force: the seed resolves a predicted collision by moving z (the ALM,
/// alm.hpp), which a driven body cannot do; `tcbench neural experiment`
/// measures that resolution.
///
/// Budget: each evaluation charges work::kNetworkEvaluation and is skipped
/// once the budget has expired; a body not evaluated in a step keeps its
/// last verdict (0 before its first evaluation).
/// Bodies that are not latent-driven are not judged (verdict 0). init()
/// throws InputError when no body is latent-driven, when a latent body's
/// scene names no model, or when the model cannot be loaded or does not take
/// the family's latent size.

#include <optional>
#include <vector>

#include "method/handler/collision_handler.hpp"
#include "method/neural/mlp.hpp"

namespace tcb {

class NeuralHandler final : public CollisionHandler {
 public:
  void init(const World& world, const CollisionSettings& settings) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override { return m_no_contacts; }
  bool reports_points() const override { return false; }
  std::vector<char> self_collision_verdicts(const World&) const override { return m_verdicts; }
  /// The last logit per body (NaN for bodies never evaluated or not latent).
  const std::vector<double>& logits() const { return m_logits; }

 private:
  std::vector<std::optional<neural::Mlp<double>>> m_networks;  ///< per body; empty: not latent-driven
  std::vector<char> m_verdicts;
  std::vector<double> m_logits;
  std::vector<Contact> m_no_contacts;
};

}  // namespace tcb
