#pragma once
/// The method against the exact oracle (oracle/), on the positions the
/// handler just saw, on the run's oracle schedules (--oracle, --oracle-volume).
/// Oracle time is oracle_ms, never handling time.
///
/// On oracle steps: the inside sets and true depths (compute_inside_oracle),
/// compared with the handler's contacts (oracle_comparison.hpp), and the
/// intersecting surface triangle pairs (FCL). On overlap steps: the exact
/// overlap volume of all pairs (corefinement; a step whose pairs cannot all
/// be measured has no value, never a silent 0). The frames are handed to the
/// meters after this one (StepContext::oracle, ::overlap: latency, tunnelling).
///
/// Columns oracle_points, recall, precision, depth_err_mean, depth_err_max,
/// max_depth, overlap_volume (m^3), triangle_pairs, oracle_ms. Summary
/// recall_min, recall_mean, precision_min, depth_err {mean, rms, max},
/// max_depth (m), oracle_steps, oracle_ms, overlap_volume_max (m^3),
/// overlap_steps, overlap_invalid_steps; null where the oracle never ran.
///
/// Self-collision per frame (summary self_frames): on each oracle step, for
/// each body whose self-collision is handled (self_collision_active), the
/// truth is whether the oracle finds some point of it strictly inside a tet
/// of its own: any self-collision point of the inside set, with or without a
/// true depth (oracle/self_depth.hpp); the method's verdict its
/// self_collision_verdicts() (for point methods: it holds such a point).
/// The neural detector's training label counts only points with a true
/// depth (oracle/self_penetration.hpp); on finger_curl every self-collision
/// point has one, so there the two truths coincide.
///
/// Per part (summary self_parts), for point methods on bodies with parts
/// (TetMesh::tet_part): each oracle frame and part is judged, the truth
/// whether some self-collision point lies in the part (a vertex lies in the
/// parts of its tets), the verdict whether the method holds such a point in
/// it. {judged, tp, fp, fn, tn, recall, precision}; null without such
/// bodies. A whole-object detector has no per-part verdict (the network has
/// one output): null for it.
/// self_frames = {frames, tp, fp, fn, tn, recall, precision, accuracy}; null
/// without such bodies or oracle steps; recall (precision) null without
/// positive truths (verdicts). A whole-body detector (`neural`,
/// reports_points() false) lists no points: its point-level recall,
/// precision and depth errors are null, said in oracle_unmeasured, and
/// self_frames is its measure. A point method's frame verdict is the weakest
/// use of its points: a frame with one of many self-colliding points found
/// counts as a true positive.

#include <memory>
#include <set>

#include "experiments/metrics/meter.hpp"
#include "oracle/inside_oracle.hpp"
#include "oracle/overlap_volume.hpp"
#include "oracle/triangle_pairs.hpp"

namespace tcb {

class OracleMeter final : public Meter {
 public:
  explicit OracleMeter(const RunSetup& run);
  std::vector<ColumnSpec> columns() const override;
  void before_dynamics(StepContext& ctx) override;
  void summarize(Json& summary) const override;

 private:
  void judge_self_frames(const StepContext& ctx);
  void judge_self_parts(const StepContext& ctx, std::size_t body);
  OracleSchedule m_oracle, m_overlap;
  std::unique_ptr<SurfaceTrianglePairs> m_triangle_pairs;
  OracleFrame m_frame;      // this step's, handed on through StepContext
  OverlapFrame m_overlap_frame;
  std::vector<double> m_recalls, m_precisions, m_depth_errors, m_self_depth_errors, m_oracle_ms;
  std::int64_t m_self_points = 0, m_self_points_with_depth = 0;
  double m_max_depth = 0.0;
  std::optional<double> m_overlap_max;
  std::int64_t m_oracle_steps = 0, m_overlap_steps = 0, m_overlap_invalid_steps = 0;
  std::int64_t m_frames_tp = 0, m_frames_fp = 0, m_frames_fn = 0, m_frames_tn = 0;
  std::int64_t m_parts_tp = 0, m_parts_fp = 0, m_parts_fn = 0, m_parts_tn = 0;
  bool m_points_reported = true;
  std::set<std::string> m_unmeasured;  // a reason repeats on every step it holds
};

}  // namespace tcb
