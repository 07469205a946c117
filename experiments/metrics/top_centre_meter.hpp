#pragma once
/// Whether a stack still stands (summary top_centre_height_m {initial,
/// final}, m): the highest centre of mass of a dynamic body along -gravity
/// (along y without gravity), at the start and at the end of the run. A
/// collapse need not be tunnelling, so it is measured on its own. Null
/// without dynamic bodies or when the final state is not finite.

#include <optional>

#include "experiments/metrics/meter.hpp"

namespace tcb {

/// The highest centre of mass of a dynamic body along -gravity (y without
/// gravity), m; nullopt without dynamic bodies.
std::optional<double> top_centre_height_m(const World& world);

class TopCentreMeter final : public Meter {
 public:
  explicit TopCentreMeter(const RunSetup& run) : m_world(run.world), m_initial(top_centre_height_m(run.world)) {}
  void summarize(Json& summary) const override;

 private:
  const World& m_world;
  std::optional<double> m_initial;
};

}  // namespace tcb
