#include "method/handler/stage_costs.hpp"

#include <numeric>

namespace tcb {

std::string_view cost_stage_name(CostStage stage) {
  switch (stage) {
    case CostStage::Prioritize: return "prioritize";
    case CostStage::HashTets: return "hash_tets";
    case CostStage::QueryPoints: return "query_points";
    case CostStage::HashSurface: return "hash_surface";
    case CostStage::BorderDepth: return "border_depth";
    case CostStage::Propagate: return "propagate";
    case CostStage::Forces: return "forces";
    case CostStage::Apply: return "apply";
  }
  return "?";
}

double StageCosts::total_ms() const { return std::accumulate(ms.begin(), ms.end(), 0.0); }

std::uint64_t StageCosts::total_work() const { return std::accumulate(work.begin(), work.end(), std::uint64_t{0}); }

}  // namespace tcb
