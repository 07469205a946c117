#pragma once
/// summary.csv: one row per run of a results directory, from each run's
/// run.json: who ran (scene, method, budget, seed, threads and the cores'
/// handover ratios, mesh order, overrides), how it ended,
/// and every number and string of its summary, nested keys joined with '.'
/// (handling_ms.p50, depth_err.max). A run without a complete run.json has a
/// row with its status ("failed", "missing") and empty figures. Written
/// atomically.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tcb {

struct SummaryRow {
  std::string run;                      ///< the run's directory name
  std::optional<nlohmann::json> record;  ///< run.json, when complete
  std::string status;                   ///< used when record is empty
};

/// Reads DIR/run.json when the run is complete: run.json parses and has a
/// summary and a status, and DIR/steps.csv beside it agrees with it (a
/// header, then exactly `steps` rows, each with the header's column count).
/// nullopt otherwise: `sweep --resume` reruns such a run.
std::optional<nlohmann::json> read_complete_run(const std::filesystem::path& run_dir);

/// A summary metric by dotted name ("handling_ms.p50"): whether the summary
/// has that key at all (null counts, as does a member of a null group: not
/// measured), and its value (nullopt when absent, null or not a number).
struct SummaryLookup {
  bool known = false;
  std::optional<double> value;
};
SummaryLookup find_summary_metric(const nlohmann::json& run, const std::string& dotted);

/// find_summary_metric(run, dotted).value.
std::optional<double> summary_metric(const nlohmann::json& run, const std::string& dotted);

/// A CSV cell: quoted (with "" for ") when it holds a comma, a quote or a newline.
std::string csv_cell(const std::string& text);

void write_summary_csv(const std::filesystem::path& path, const std::vector<SummaryRow>& rows);

}  // namespace tcb
