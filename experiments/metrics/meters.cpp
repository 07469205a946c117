#include "experiments/metrics/meters.hpp"

#include "experiments/metrics/contact_solve_meter.hpp"
#include "experiments/metrics/divergence_meter.hpp"
#include "experiments/metrics/dynamics_meter.hpp"
#include "experiments/metrics/energy_meter.hpp"
#include "experiments/metrics/force_reference_meter.hpp"
#include "experiments/metrics/handling_meter.hpp"
#include "experiments/metrics/jitter.hpp"
#include "experiments/metrics/latency.hpp"
#include "experiments/metrics/oracle_meter.hpp"
#include "experiments/metrics/probe_force_meter.hpp"
#include "experiments/metrics/settled_meter.hpp"
#include "experiments/metrics/stability_meter.hpp"
#include "experiments/metrics/stage_meter.hpp"
#include "experiments/metrics/step_cost_meter.hpp"
#include "experiments/metrics/top_centre_meter.hpp"
#include "experiments/metrics/tunneling_meter.hpp"
#include "experiments/metrics/timing_meter.hpp"
#include "experiments/metrics/work_meter.hpp"

namespace tcb {

std::vector<std::unique_ptr<Meter>> make_meters(const RunSetup& run) {
  std::vector<std::unique_ptr<Meter>> meters;
  meters.push_back(std::make_unique<HandlingMeter>(run));
  meters.push_back(std::make_unique<TimingMeter>(run));
  meters.push_back(std::make_unique<WorkMeter>());
  meters.push_back(std::make_unique<OracleMeter>(run));  // before the meters that read its frames
  meters.push_back(std::make_unique<LatencyMeter>(run));
  meters.push_back(std::make_unique<TunnelingMeter>(run));
  meters.push_back(std::make_unique<DynamicsMeter>(run));
  meters.push_back(std::make_unique<StepCostMeter>());
  meters.push_back(std::make_unique<StageMeter>());
  meters.push_back(std::make_unique<ForceReferenceMeter>(run));
  meters.push_back(std::make_unique<DivergenceMeter>(run));
  meters.push_back(std::make_unique<StabilityMeter>(run));
  meters.push_back(std::make_unique<EnergyMeter>(run));  // after stability: a NaN is named as such
  meters.push_back(std::make_unique<JitterMeter>(run));
  meters.push_back(std::make_unique<TopCentreMeter>(run));
  meters.push_back(std::make_unique<ProbeForceMeter>());
  meters.push_back(std::make_unique<ContactSolveMeter>());
  meters.push_back(std::make_unique<SettledMeter>(run));
  return meters;
}

}  // namespace tcb
