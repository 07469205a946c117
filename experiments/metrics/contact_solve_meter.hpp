#pragma once
/// What implicit contact cost the integrator (World::last_contact_solve,
/// sim/world/coupled_solve.hpp). Column contact_links (links handed to the
/// step's solve; 0 under explicit response). Summary contact_links_max,
/// unilateral_resolve_steps (steps in which some component dropped pulling
/// links and was solved again), unilateral_dropped_links (links dropped, over
/// the run), unilateral_still_pulling (links still pulling after the second
/// solve, over the run) and contact_solve_unconverged_steps.

#include "experiments/metrics/meter.hpp"

namespace tcb {

class ContactSolveMeter final : public Meter {
 public:
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  std::int64_t m_links_max = 0, m_resolve_steps = 0, m_dropped = 0, m_still_pulling = 0, m_unconverged = 0;
};

}  // namespace tcb
