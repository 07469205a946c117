#include "experiments/results/steps_csv.hpp"

#include <fmt/format.h>

namespace tcb {
namespace {

template <typename T>
std::string cell(const std::optional<T>& v) {
  return v ? fmt::format("{}", *v) : std::string();
}

}  // namespace

const std::vector<std::string>& StepsCsv::columns() {
  static const std::vector<std::string> names = {
      "step",          "time_s",           "handling_ms",    "budget_ms",      "work_units",
      "cycle",         "cycle_done",       "colliding_points", "exact_forces", "estimated_forces",
      "oracle_points", "recall",           "precision",      "depth_err_mean", "depth_err_max",
      "max_depth",     "overlap_volume",   "triangle_pairs", "oracle_ms",      "kinetic_energy",
      "dynamics_ms",   "max_speed",        "solver_iterations", "probe_force_x", "probe_force_y",
      "probe_force_z"};
  return names;
}

StepsCsv::StepsCsv(const std::filesystem::path& path) : m_file(path) {
  const auto& names = columns();
  for (std::size_t i = 0; i < names.size(); ++i) m_file.stream() << (i ? "," : "") << names[i];
  m_file.stream() << '\n';
}

void StepsCsv::write(const StepRow& r) {
  m_file.stream() << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.step,
                                 r.time_s, cell(r.handling_ms), cell(r.budget_ms), cell(r.work_units), cell(r.cycle),
                                 cell(r.cycle_done), cell(r.colliding_points), cell(r.exact_forces),
                                 cell(r.estimated_forces), cell(r.oracle_points), cell(r.recall), cell(r.precision),
                                 cell(r.depth_err_mean), cell(r.depth_err_max), cell(r.max_depth),
                                 cell(r.overlap_volume), cell(r.triangle_pairs), cell(r.oracle_ms), r.kinetic_energy, r.dynamics_ms,
                                 r.max_speed, r.solver_iterations, cell(r.probe_force_x), cell(r.probe_force_y),
                                 cell(r.probe_force_z));
}

}  // namespace tcb
