#pragma once
/// Energy bookkeeping: whether the run creates energy it was never given.
///
/// E(t) = kinetic + elastic + gravitational energy of the dynamic bodies
/// after step t (World::total_energy_j). W(t) = the work driven bodies did on
/// them through their contacts up to step t (World::driven_work_j). Nothing
/// else works on them from outside: a static passive body and the ground do
/// not move where they touch, so in exact mechanics they only take energy
/// away (inelastic impact, friction). Without numerical error, and with
/// conservative contacts, E(t) <= E(0) + W(t): the implicit integrator and
/// its Rayleigh damping only dissipate, and what penalty contacts store is
/// not counted in E. The rise
///
///   gain(t) = E(t) - E(0) - W(t)   (J)
///
/// is therefore energy the simulation made: its integrator, its contact
/// forces (a method's stale or extrapolated ones among them), or its ground.
/// The ground projection (sim/world/ground.hpp) lifts vertices the step
/// carried below the plane, which compresses their tets against the weight
/// they carry: energy from nothing, which the integrator's dissipation
/// mostly cancels while a body rests, but not when a stiff body lands fast
/// or a tall stack settles. Telling that share apart from the rest would
/// need the ground inside the solve; method `none` on a scene measures it.
/// Both gains below are relative to the energy the run had to spend,
///
///   S(t) = K(0) + U_el(0) + sum over dynamic vertices of m |g| h0
///          + max(0, max over s <= t of W(s)),
///
/// h0 a vertex's initial height above the lowest level it could fall to (the
/// ground where there is one, else the lowest initial vertex of any body,
/// along g). energy_gain = max over t of gain(t) / S(t): 0.3 means the run
/// at some step held 30 % more energy than it started with and was given.
///
/// The verdict reads the energy of motion and height alone:
/// motion_energy_gain = max over t of (K(t) + U_g(t) - E(0) - W(t)) / S(t),
/// the same rise without the elastic energy stored at step t. A stiff body
/// the ground projection lifts holds a spike of elastic energy for a few
/// steps that the integrator's damping takes straight back (sneaker_grass
/// under `none`: energy_gain 6.1 at step 103, gone ten steps later, the shoe
/// then moving with less kinetic energy than before it landed), which is no
/// explosion; energy that has turned into motion or height is. Above the scene's max_energy_gain
/// (default 0.5) the run is unstable, with the step and the figures in the
/// reason; below it both gains are measurements.
///
/// Columns total_energy (J), driven_work (J, cumulative). Summary
/// energy_gain and motion_energy_gain (relative; null when S stayed 0:
/// nothing had energy and nothing gave any) and energy {initial_j, final_j,
/// available_j, gain_max_j, gain_step, motion_gain_step, driven_work_j,
/// bound}.
/// Cost, outside every timed interval: one elastic energy evaluation per
/// step (a rotation extraction per tet).

#include <cstdint>

#include "experiments/metrics/meter.hpp"

namespace tcb {

/// The energy a world's dynamic bodies could release at its start (J): S(0) above.
double available_energy_j(const World& world);

class EnergyMeter final : public Meter {
 public:
  explicit EnergyMeter(const RunSetup& run);
  std::vector<ColumnSpec> columns() const override;
  void on_step(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  const World& m_world;
  double m_bound;
  double m_initial_j = 0.0, m_available0_j = 0.0, m_work_max_j = 0.0;
  double m_final_j = 0.0;
  double m_gain_max_j = 0.0, m_gain_max_rel = 0.0, m_motion_gain_max_rel = 0.0;
  std::int64_t m_gain_step = 0, m_motion_gain_step = 0;
  bool m_judged = false;  ///< S > 0 at some step
};

}  // namespace tcb
