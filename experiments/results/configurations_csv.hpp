#pragma once
/// configurations.csv: one row per configuration of a results directory
/// (run_collection.hpp: the runs that differ only by seed), so a sweep with
/// several seeds reports rates and medians with intervals instead of single
/// observations. Columns: configuration (in words), scene, method, budget,
/// response, overrides (joined by spaces), runs, seeds (joined by spaces);
/// the outcomes as count, runs judged and Wilson 95 % interval
/// (unstable: status; tunnelling: summary.tunneling > 0, among runs that
/// measured it); then per headline metric M (headline_metrics()): M.median,
/// M.ci95_lo, M.ci95_hi (bootstrap_interval.hpp; empty below 2 values), M.n.
/// Written atomically.

#include <filesystem>
#include <vector>

#include "experiments/results/run_collection.hpp"

namespace tcb {

void write_configurations_csv(const std::filesystem::path& path, const std::vector<CollectedRun>& runs);

}  // namespace tcb
