#pragma once
/// The meters every run carries, in the order their columns appear in
/// steps.csv and their keys in the summary. Adding a metric: one meter file
/// in this folder and one line in meters.cpp.

#include <memory>
#include <vector>

#include "experiments/metrics/meter.hpp"

namespace tcb {

std::vector<std::unique_ptr<Meter>> make_meters(const RunSetup& run);

}  // namespace tcb
