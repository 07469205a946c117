#pragma once
/// steps.csv: one row per simulation step. The first two columns are the
/// run's own (step, time_s); every other column is declared by the meter that
/// measures it (experiments/metrics/meter.hpp), in the order the meters are
/// registered, with its meaning and unit (docs/contract.md lists them all). A
/// value that was not measured this step (no handler, oracle off) is an empty
/// cell, never 0. Written to steps.csv.tmp as the run goes and renamed by
/// commit(), so an interrupted run never leaves a steps.csv that looks complete.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sim/io/atomic_file.hpp"

namespace tcb {

/// One column: its name and what it holds, with the unit.
struct ColumnSpec {
  std::string name;
  std::string meaning;
};

/// The cells of one row, by column name. Setting a column that was not
/// declared is a programming error (std::logic_error), caught by every run.
class StepRow {
 public:
  explicit StepRow(const std::map<std::string, std::size_t, std::less<>>* index = nullptr);
  void set(std::string_view column, double value);
  void set(std::string_view column, std::int64_t value);
  const std::vector<std::string>& cells() const { return m_cells; }

 private:
  std::string& cell(std::string_view column);
  const std::map<std::string, std::size_t, std::less<>>* m_index;
  std::vector<std::string> m_cells;
};

class StepsCsv {
 public:
  StepsCsv(const std::filesystem::path& path, std::vector<ColumnSpec> columns);
  /// An empty row for these columns.
  StepRow row() const { return StepRow(&m_index); }
  void write(const StepRow& row);
  void commit() { m_file.commit(); }
  const std::vector<ColumnSpec>& columns() const { return m_columns; }

 private:
  AtomicFile m_file;
  std::vector<ColumnSpec> m_columns;
  std::map<std::string, std::size_t, std::less<>> m_index;
};

}  // namespace tcb
