#include "experiments/metrics/meter.hpp"

#include "experiments/metrics/distribution.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

OracleSchedule parse_oracle_schedule(const std::string& text, const std::string& option) {
  if (text == "off") return {0};
  if (text == "every") return {1};
  if (text.rfind("every:", 0) == 0) {
    try {
      std::size_t used = 0;
      const long long k = std::stoll(text.substr(6), &used);
      if (used == text.size() - 6 && k >= 1) return {k};
    } catch (const std::exception&) {
    }
  }
  throw InputError(option, 0, "expected off, every or every:K with K >= 1, not '" + text + "'");
}

void note_unmeasured(nlohmann::ordered_json& summary, const std::string& reason) {
  summary["oracle_unmeasured"].push_back(reason);
}

nlohmann::ordered_json distribution_json(const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  const Distribution d = summarize(values);
  return {{"mean", d.mean}, {"p50", d.p50}, {"p95", d.p95}, {"p99", d.p99}, {"max", d.max}};
}

}  // namespace tcb
