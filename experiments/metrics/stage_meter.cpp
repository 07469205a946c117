#include "experiments/metrics/stage_meter.hpp"

#include <algorithm>

namespace tcb {
namespace {

std::string column_of(std::size_t stage) {
  return "stage_" + std::string(cost_stage_name(static_cast<CostStage>(stage))) + "_ms";
}

std::string work_column_of(std::size_t stage) {
  return "stage_" + std::string(cost_stage_name(static_cast<CostStage>(stage))) + "_work";
}

constexpr std::size_t kApply = static_cast<std::size_t>(CostStage::Apply);  // charges no work

}  // namespace

std::vector<ColumnSpec> StageMeter::columns() const {
  std::vector<ColumnSpec> out;
  for (std::size_t s = 0; s < kCostStages; ++s) {
    const auto name = cost_stage_name(static_cast<CostStage>(s));
    out.push_back({column_of(s), s + 1 == kCostStages
                                     ? std::string("handling time outside the collision cycle: applying forces, "
                                                   "extrapolating, the handler's bookkeeping (ms)")
                                     : "handling time in the cycle's " + std::string(name) + " stage (ms)"});
  }
  for (std::size_t s = 0; s < kApply; ++s)
    out.push_back({work_column_of(s), "work units charged in the cycle's " +
                                          std::string(cost_stage_name(static_cast<CostStage>(s))) +
                                          " stage this step (they add up to work_units)"});
  out.push_back({"interrupted_stage",
                 "the stage the budget stopped the cycle in (0 prioritize, 1 hash_tets, 2 query_points, 3 "
                 "hash_surface, 4 border_depth, 5 propagate, 6 forces); empty when not interrupted"});
  return out;
}

void StageMeter::on_step(StepContext& ctx) {
  const StageCosts& c = ctx.report.stages;
  for (std::size_t s = 0; s < kCostStages; ++s) {
    ctx.row.set(column_of(s), c.ms[s]);
    m_ms_sum[s] += c.ms[s];
    m_ms_max[s] = std::max(m_ms_max[s], c.ms[s]);
    m_work_sum[s] += static_cast<double>(c.work[s]);
    if (s < kApply) ctx.row.set(work_column_of(s), static_cast<std::int64_t>(c.work[s]));
  }
  if (c.interrupted >= 0) {
    ctx.row.set("interrupted_stage", std::int64_t{c.interrupted});
    ++m_interrupted[static_cast<std::size_t>(c.interrupted)];
  }
  m_unaccounted_sum += ctx.handling_ms - c.total_ms();
  ++m_steps;
}

void StageMeter::summarize(Json& summary) const {
  const double n = static_cast<double>(std::max<std::int64_t>(m_steps, 1));
  Json stages = Json::object();
  for (std::size_t s = 0; s < kCostStages; ++s) {
    stages[std::string(cost_stage_name(static_cast<CostStage>(s)))] = {{"ms_mean", m_ms_sum[s] / n},
                                                                       {"ms_max", m_ms_max[s]},
                                                                       {"work_mean", m_work_sum[s] / n},
                                                                       {"interrupted_steps", m_interrupted[s]}};
  }
  summary["stages"] = m_steps > 0 ? stages : Json(nullptr);
  summary["stages_ms_unaccounted_mean"] = m_steps > 0 ? Json(m_unaccounted_sum / n) : Json(nullptr);
}

}  // namespace tcb
