#include "experiments/results/steps_csv.hpp"

#include <fmt/format.h>

namespace tcb {
namespace {

// One table of (name, value): the header and every row come from it, so the
// two cannot drift apart when a column is added.
template <typename T>
std::string text(const std::optional<T>& v) {
  return v ? fmt::format("{}", *v) : std::string();  // not measured: an empty cell, never 0
}
template <typename T>
std::string text(const T& v) {
  return fmt::format("{}", v);
}
template <auto Member>
std::string field(const StepRow& r) {
  return text(r.*Member);
}

struct Column {
  const char* name;
  std::string (*value)(const StepRow&);
};

const std::vector<Column>& table() {
  static const std::vector<Column> columns = {
      {"step", field<&StepRow::step>},
      {"time_s", field<&StepRow::time_s>},
      {"handling_ms", field<&StepRow::handling_ms>},
      {"budget_ms", field<&StepRow::budget_ms>},
      {"work_units", field<&StepRow::work_units>},
      {"cycle", field<&StepRow::cycle>},
      {"cycle_done", field<&StepRow::cycle_done>},
      {"colliding_points", field<&StepRow::colliding_points>},
      {"exact_forces", field<&StepRow::exact_forces>},
      {"estimated_forces", field<&StepRow::estimated_forces>},
      {"oracle_points", field<&StepRow::oracle_points>},
      {"recall", field<&StepRow::recall>},
      {"precision", field<&StepRow::precision>},
      {"depth_err_mean", field<&StepRow::depth_err_mean>},
      {"depth_err_max", field<&StepRow::depth_err_max>},
      {"max_depth", field<&StepRow::max_depth>},
      {"overlap_volume", field<&StepRow::overlap_volume>},
      {"triangle_pairs", field<&StepRow::triangle_pairs>},
      {"oracle_ms", field<&StepRow::oracle_ms>},
      {"kinetic_energy", field<&StepRow::kinetic_energy>},
      {"dynamics_ms", field<&StepRow::dynamics_ms>},
      {"max_speed", field<&StepRow::max_speed>},
      {"solver_iterations", field<&StepRow::solver_iterations>},
      {"probe_force_x", field<&StepRow::probe_force_x>},
      {"probe_force_y", field<&StepRow::probe_force_y>},
      {"probe_force_z", field<&StepRow::probe_force_z>},
  };
  return columns;
}

}  // namespace

const std::vector<std::string>& StepsCsv::columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Column& c : table()) n.emplace_back(c.name);
    return n;
  }();
  return names;
}

StepsCsv::StepsCsv(const std::filesystem::path& path) : m_file(path) {
  const auto& names = columns();
  for (std::size_t i = 0; i < names.size(); ++i) m_file.stream() << (i ? "," : "") << names[i];
  m_file.stream() << '\n';
}

void StepsCsv::write(const StepRow& r) {
  const auto& columns = table();
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i) line += ',';
    line += columns[i].value(r);
  }
  line += '\n';
  m_file.stream() << line;
}

}  // namespace tcb
