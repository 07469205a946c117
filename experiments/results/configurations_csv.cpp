#include "experiments/results/configurations_csv.hpp"

#include <fmt/format.h>

#include <cmath>

#include "experiments/results/summary_csv.hpp"
#include "experiments/statistics/bootstrap_interval.hpp"
#include "experiments/statistics/wilson_interval.hpp"
#include "sim/io/atomic_file.hpp"

namespace tcb {
namespace {

std::string number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string(); }

void add_rate(std::vector<std::string>& row, std::size_t count, std::size_t judged) {
  const auto w = wilson_interval(count, judged);
  row.push_back(std::to_string(count));
  row.push_back(std::to_string(judged));
  row.push_back(w ? number(w->lo) : "");
  row.push_back(w ? number(w->hi) : "");
}

void append_word(std::string& list, const std::string& word) {
  if (!list.empty()) list += ' ';
  list += word;
}

void append_row(std::string& text, const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) text += ',';
    text += csv_cell(cells[i]);
  }
  text += '\n';
}

}  // namespace

void write_configurations_csv(const std::filesystem::path& path, const std::vector<CollectedRun>& runs) {
  std::vector<std::string> header = {"configuration", "scene",    "method", "budget", "response", "overrides",
                                     "runs",          "seeds"};
  for (const char* outcome : {"unstable", "tunnelling"})
    for (const char* part : {"", "_runs", "_ci95_lo", "_ci95_hi"}) header.push_back(std::string(outcome) + part);
  for (const std::string& m : headline_metrics())
    for (const char* part : {".median", ".ci95_lo", ".ci95_hi", ".n"}) header.push_back(m + part);
  std::string text;
  append_row(text, header);
  for (const auto& group : group_repeats(runs)) {
    const nlohmann::json& first = group.front()->record;
    std::string overrides, seeds;
    for (const auto& o : first.value("overrides", nlohmann::json::array()))
      append_word(overrides, o.get<std::string>());
    std::size_t unstable = 0, tunnelled = 0, tunnel_judged = 0;
    for (const CollectedRun* r : group) {
      append_word(seeds, std::to_string(r->record.value("seed", std::uint64_t{0})));
      unstable += r->record.value("status", "") == "unstable";
      if (const auto t = summary_metric(r->record, "tunneling")) {
        ++tunnel_judged;
        tunnelled += *t > 0.0;
      }
    }
    std::vector<std::string> row = {configuration_label(first),
                                    first.value("scene", ""),
                                    first.value("method_label", first.value("method", "")),
                                    first.value("budget", nlohmann::json::object()).value("label", "none"),
                                    first.value("response", "explicit"),
                                    overrides,
                                    std::to_string(group.size()),
                                    seeds};
    add_rate(row, unstable, group.size());
    add_rate(row, tunnelled, tunnel_judged);
    for (const std::string& m : headline_metrics()) {
      std::vector<double> values;
      for (const CollectedRun* r : group)
        if (const auto v = summary_metric(r->record, m); v && std::isfinite(*v)) values.push_back(*v);
      const MedianEstimate e = bootstrap_median(values);
      row.push_back(values.empty() ? "" : number(e.median));
      row.push_back(e.ci95 ? number(e.ci95->lo) : "");
      row.push_back(e.ci95 ? number(e.ci95->hi) : "");
      row.push_back(std::to_string(values.size()));
    }
    append_row(text, row);
  }
  write_file_atomically(path, text);
}

}  // namespace tcb
