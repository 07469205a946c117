#include "experiments/results/steps_csv.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace tcb {

StepRow::StepRow(const std::map<std::string, std::size_t, std::less<>>* index) : m_index(index) {
  if (m_index) m_cells.resize(m_index->size());
}

std::string& StepRow::cell(std::string_view column) {
  if (m_index)
    if (const auto it = m_index->find(column); it != m_index->end()) return m_cells[it->second];
  throw std::logic_error("steps.csv: no column '" + std::string(column) + "' was declared");
}

void StepRow::set(std::string_view column, double value) { cell(column) = fmt::format("{}", value); }
void StepRow::set(std::string_view column, std::int64_t value) { cell(column) = fmt::format("{}", value); }

StepsCsv::StepsCsv(const std::filesystem::path& path, std::vector<ColumnSpec> columns)
    : m_file(path), m_columns(std::move(columns)) {
  for (std::size_t i = 0; i < m_columns.size(); ++i) {
    if (!m_index.emplace(m_columns[i].name, i).second)
      throw std::logic_error("steps.csv: column '" + m_columns[i].name + "' declared twice");
    m_file.stream() << (i ? "," : "") << m_columns[i].name;
  }
  m_file.stream() << '\n';
}

void StepsCsv::write(const StepRow& row) {
  std::string line;
  for (std::size_t i = 0; i < row.cells().size(); ++i) {
    if (i) line += ',';
    line += row.cells()[i];
  }
  line += '\n';
  m_file.stream() << line;
}

}  // namespace tcb
