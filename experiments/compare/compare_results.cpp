#include "experiments/compare/compare_results.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "experiments/results/summary_csv.hpp"
#include "experiments/statistics/wilson_interval.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {
namespace {

constexpr double kAlpha = 0.05;

/// The metric's value in each run that has it as a finite number.
std::vector<double> values_of(const std::vector<const CollectedRun*>& runs, const std::string& metric) {
  std::vector<double> out;
  for (const CollectedRun* r : runs)
    if (const auto v = summary_metric(r->record, metric); v && std::isfinite(*v)) out.push_back(*v);
  return out;
}

/// The steps.csv column a timing metric summarizes: handling_ms.p50 -> handling_ms.
std::string column_of(const std::string& metric) { return metric.substr(0, metric.find('.')); }

/// A column's finite values over the runs' steps.csv, pooled.
std::vector<double> step_values(const std::vector<const CollectedRun*>& runs, const std::string& column) {
  std::vector<double> out;
  for (const CollectedRun* r : runs) {
    std::ifstream in(r->dir / "steps.csv");
    std::string line;
    if (!std::getline(in, line)) continue;
    std::vector<std::string> header;
    std::stringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
    const auto at = std::find(header.begin(), header.end(), column);
    if (at == header.end()) continue;
    const std::size_t index = static_cast<std::size_t>(at - header.begin());
    while (std::getline(in, line)) {
      std::stringstream row(line);
      std::string cell;
      for (std::size_t i = 0; i <= index && std::getline(row, cell, ','); ++i) {
      }
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (!cell.empty() && end != cell.c_str() && std::isfinite(v)) out.push_back(v);
    }
  }
  return out;
}

OutcomeComparison outcome(const std::string& name, const std::vector<const CollectedRun*>& a,
                          const std::vector<const CollectedRun*>& b) {
  // unstable: the run's status; tunnelling: summary.tunneling > 0 (runs where it is not measured do not count).
  const auto tally = [&](const std::vector<const CollectedRun*>& runs, std::size_t& count, std::size_t& total) {
    for (const CollectedRun* r : runs) {
      if (name == "unstable") {
        ++total;
        count += r->record.value("status", "") == "unstable";
      } else if (const auto t = summary_metric(r->record, "tunneling")) {
        ++total;
        count += *t > 0.0;
      }
    }
  };
  OutcomeComparison o{name};
  tally(a, o.a_count, o.a_runs);
  tally(b, o.b_count, o.b_runs);
  return o;
}

ThresholdVerdict judge(const CompareThreshold& t, const MetricComparison& m) {
  ThresholdVerdict v{&t, "pass", ""};
  double change = m.difference.median;
  if (t.relative) {
    if (!m.relative) return {&t, "fail", "A's median is 0: a relative limit cannot be judged"};
    change = 100.0 * *m.relative;
  }
  const bool beyond = t.direction == CompareThreshold::Direction::Rise   ? change > t.limit
                      : t.direction == CompareThreshold::Direction::Fall ? -change > t.limit
                                                                         : std::abs(change) > t.limit;
  const std::string unit = t.relative ? " %" : "";
  if (!beyond) {
    v.why = fmt::format("change {:+.4g}{} within {}", change, unit, t.text.substr(t.text.find('=') + 1));
    return v;
  }
  if (is_timing_metric(t.metric) && (!m.u_test || m.u_test->p_two_sided >= kAlpha)) {
    v.why = fmt::format("change {:+.4g}{} beyond the limit but not significant (U test p = {})", change, unit,
                        m.u_test ? fmt::format("{:.3g}", m.u_test->p_two_sided) : std::string("n/a"));
    return v;
  }
  v.status = "fail";
  v.why = fmt::format("change {:+.4g}{} beyond {}", change, unit, t.text.substr(t.text.find('=') + 1));
  if (m.u_test) v.why += fmt::format(" (U test p = {:.3g} over {})", m.u_test->p_two_sided, m.u_over);
  return v;
}

ComparedPair compare_pair(const std::vector<const CollectedRun*>& a, const std::vector<const CollectedRun*>& b,
                          const std::vector<std::string>& metrics, const std::vector<CompareThreshold>& thresholds) {
  ComparedPair p;
  p.a_label = configuration_label(a.front()->record);
  p.b_label = configuration_label(b.front()->record);
  p.a_runs = a.size();
  p.b_runs = b.size();
  std::vector<std::string> wanted = metrics;
  for (const CompareThreshold& t : thresholds)
    if (std::find(wanted.begin(), wanted.end(), t.metric) == wanted.end()) wanted.push_back(t.metric);
  for (const std::string& metric : wanted) {
    const std::vector<double> va = values_of(a, metric), vb = values_of(b, metric);
    if (va.empty() || vb.empty()) continue;
    MetricComparison m;
    m.metric = metric;
    m.a = bootstrap_median(va);
    m.b = bootstrap_median(vb);
    m.difference = bootstrap_median_difference(va, vb);
    if (m.a.median != 0.0) m.relative = m.difference.median / std::abs(m.a.median);
    if (va.size() >= 3 && vb.size() >= 3) {
      m.u_test = mann_whitney(va, vb);
      m.u_over = "runs";
    } else if (is_timing_metric(metric)) {
      m.u_test = mann_whitney(step_values(a, column_of(metric)), step_values(b, column_of(metric)));
      m.u_over = "steps";
    }
    for (const CompareThreshold& t : thresholds)
      if (t.metric == metric) p.verdicts.push_back(judge(t, m));
    p.metrics.push_back(std::move(m));
  }
  for (const char* name : {"unstable", "tunnelling"}) {
    OutcomeComparison o = outcome(name, a, b);
    if (o.a_runs && o.b_runs) p.outcomes.push_back(o);
  }
  return p;
}

std::string estimate_text(const MedianEstimate& e) {
  if (!e.ci95) return fmt::format("{:.4g}", e.median);
  return fmt::format("{:.4g} [{:.4g}, {:.4g}]", e.median, e.ci95->lo, e.ci95->hi);
}

std::string rate_text(std::size_t k, std::size_t n) {
  const auto w = wilson_interval(k, n);
  return fmt::format("{}/{} [{:.0f}-{:.0f} %]", k, n, 100.0 * w->lo, 100.0 * w->hi);
}

nlohmann::json estimate_json(const MedianEstimate& e) {
  nlohmann::json j = {{"median", e.median}, {"n", e.n}};
  j["ci95"] = e.ci95 ? nlohmann::json::array({e.ci95->lo, e.ci95->hi}) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json verdict_json(const ThresholdVerdict& v) {
  return {{"threshold", v.threshold->text}, {"status", v.status}, {"why", v.why}};
}

}  // namespace

CompareThreshold parse_compare_threshold(const std::string& text) {
  const auto bad = [&](const std::string& why) { return InputError("--threshold " + text, 0, why); };
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw bad("expected METRIC=LIMIT, e.g. handling_ms.p50=+10% or recall_mean=-0.01");
  CompareThreshold t;
  t.text = text;
  t.metric = text.substr(0, eq);
  std::string limit = text.substr(eq + 1);
  if (limit.front() == '+') t.direction = CompareThreshold::Direction::Rise;
  if (limit.front() == '-') t.direction = CompareThreshold::Direction::Fall;
  if (limit.front() == '+' || limit.front() == '-') limit.erase(0, 1);
  if (!limit.empty() && limit.back() == '%') {
    t.relative = true;
    limit.pop_back();
  }
  char* end = nullptr;
  t.limit = std::strtod(limit.c_str(), &end);
  if (limit.empty() || end != limit.c_str() + limit.size() || !std::isfinite(t.limit) || t.limit < 0.0 ||
      limit.front() == '+' || limit.front() == '-' || std::isspace(static_cast<unsigned char>(limit.front())))
    throw bad("the limit must be a number >= 0, optionally signed (+ may rise, - may fall) and ending in %");
  return t;
}

bool is_timing_metric(const std::string& metric) {
  const std::string column = column_of(metric);
  return column.size() > 3 && column.compare(column.size() - 3, 3, "_ms") == 0 && column != "reference_ms";
}

bool Comparison::regression() const {
  if (!unknown.empty()) return true;
  for (const ComparedPair& p : pairs)
    for (const ThresholdVerdict& v : p.verdicts)
      if (v.status != "pass") return true;
  return false;
}

Comparison compare_runs(const std::vector<CollectedRun>& a, const std::vector<CollectedRun>& b,
                        std::vector<std::string> metrics, const std::vector<CompareThreshold>& thresholds) {
  if (metrics.empty()) metrics = headline_metrics();
  const auto groups_a = group_repeats(a), groups_b = group_repeats(b);
  Comparison c;
  if (groups_a.size() == 1 && groups_b.size() == 1) {
    c.pairs.push_back(compare_pair(groups_a[0], groups_b[0], metrics, thresholds));
  } else {
    std::map<std::string, const std::vector<const CollectedRun*>*> by_key;
    for (const auto& g : groups_b) by_key[configuration_key(g.front()->record)] = &g;
    for (const auto& g : groups_a) {
      const auto it = by_key.find(configuration_key(g.front()->record));
      if (it == by_key.end()) {
        c.only_a.push_back(configuration_label(g.front()->record));
        continue;
      }
      c.pairs.push_back(compare_pair(g, *it->second, metrics, thresholds));
      by_key.erase(it);
    }
    for (const auto& g : groups_b)
      if (by_key.count(configuration_key(g.front()->record))) c.only_b.push_back(configuration_label(g.front()->record));
  }
  for (const CompareThreshold& t : thresholds) {
    bool judged = false;
    for (const ComparedPair& p : c.pairs)
      for (const ThresholdVerdict& v : p.verdicts) judged = judged || v.threshold == &t;
    if (!judged) c.unknown.push_back({&t, "unknown metric", "no paired run has '" + t.metric + "' on both sides"});
  }
  return c;
}

std::string format_comparison(const Comparison& c, const std::string& a_name, const std::string& b_name) {
  std::string out = fmt::format("tcbench compare: A = {}, B = {}\n{} pair(s) of configurations; medians over repeats "
                                "with bootstrap 95 % intervals; B - A\n",
                                a_name, b_name, c.pairs.size());
  for (const ComparedPair& p : c.pairs) {
    out += "\n";
    if (p.a_label == p.b_label)
      out += fmt::format("{}  (A: {} run(s), B: {})\n", p.a_label, p.a_runs, p.b_runs);
    else
      out += fmt::format("A: {} ({} run(s))\nB: {} ({} run(s))\n", p.a_label, p.a_runs, p.b_label, p.b_runs);
    out += fmt::format("  {:<28} {:>30} {:>30} {:>32} {:>9}  {}\n", "metric", "A", "B", "B - A", "rel", "U test");
    for (const MetricComparison& m : p.metrics)
      out += fmt::format("  {:<28} {:>30} {:>30} {:>32} {:>9}  {}\n", m.metric, estimate_text(m.a), estimate_text(m.b),
                         estimate_text(m.difference),
                         m.relative ? fmt::format("{:+.1f} %", 100.0 * *m.relative) : std::string("-"),
                         m.u_test ? fmt::format("p = {:.3g} ({} {}/{})", m.u_test->p_two_sided, m.u_over,
                                                m.u_test->n_a, m.u_test->n_b)
                                  : std::string("-"));
    for (const OutcomeComparison& o : p.outcomes)
      out += fmt::format("  {:<28} {:>30} {:>30}\n", o.outcome, rate_text(o.a_count, o.a_runs),
                         rate_text(o.b_count, o.b_runs));
    for (const ThresholdVerdict& v : p.verdicts)
      out += fmt::format("  threshold {}: {} ({})\n", v.threshold->text, v.status, v.why);
  }
  for (const std::string& s : c.only_a) out += "only in A: " + s + "\n";
  for (const std::string& s : c.only_b) out += "only in B: " + s + "\n";
  for (const ThresholdVerdict& v : c.unknown) out += fmt::format("threshold {}: {} ({})\n", v.threshold->text, v.status, v.why);
  if (c.pairs.empty()) out += "no configuration of A has a partner in B\n";
  return out;
}

nlohmann::json comparison_json(const Comparison& c, const std::string& a_name, const std::string& b_name) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const ComparedPair& p : c.pairs) {
    nlohmann::json metrics = nlohmann::json::array(), outcomes = nlohmann::json::array(),
                   verdicts = nlohmann::json::array();
    for (const MetricComparison& m : p.metrics) {
      nlohmann::json j = {{"metric", m.metric},
                          {"a", estimate_json(m.a)},
                          {"b", estimate_json(m.b)},
                          {"difference", estimate_json(m.difference)}};
      j["relative"] = m.relative ? nlohmann::json(*m.relative) : nlohmann::json(nullptr);
      j["u_test"] = m.u_test ? nlohmann::json{{"u_a", m.u_test->u_a},
                                              {"p_two_sided", m.u_test->p_two_sided},
                                              {"a_greater_share", m.u_test->a_greater_share},
                                              {"n_a", m.u_test->n_a},
                                              {"n_b", m.u_test->n_b},
                                              {"over", m.u_over}}
                             : nlohmann::json(nullptr);
      metrics.push_back(j);
    }
    for (const OutcomeComparison& o : p.outcomes) {
      const auto wa = wilson_interval(o.a_count, o.a_runs), wb = wilson_interval(o.b_count, o.b_runs);
      outcomes.push_back({{"outcome", o.outcome},
                          {"a", {{"count", o.a_count}, {"runs", o.a_runs}, {"ci95", {wa->lo, wa->hi}}}},
                          {"b", {{"count", o.b_count}, {"runs", o.b_runs}, {"ci95", {wb->lo, wb->hi}}}}});
    }
    for (const ThresholdVerdict& v : p.verdicts) verdicts.push_back(verdict_json(v));
    pairs.push_back({{"a", p.a_label}, {"b", p.b_label}, {"a_runs", p.a_runs}, {"b_runs", p.b_runs},
                     {"metrics", metrics}, {"outcomes", outcomes}, {"thresholds", verdicts}});
  }
  nlohmann::json unknown = nlohmann::json::array();
  for (const ThresholdVerdict& v : c.unknown) unknown.push_back(verdict_json(v));
  return {{"schema", "tcbench.compare/1"}, {"a", a_name},        {"b", b_name},
          {"pairs", pairs},                {"only_a", c.only_a}, {"only_b", c.only_b},
          {"unknown_thresholds", unknown}, {"bootstrap", {{"resamples", kBootstrapResamples}, {"seed", kBootstrapSeed}}},
          {"regression", c.regression()}};
}

}  // namespace tcb
