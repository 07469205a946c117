#include "experiments/metrics/oracle_meter.hpp"

#include <algorithm>
#include <chrono>

#include "experiments/metrics/distribution.hpp"
#include "experiments/metrics/oracle_comparison.hpp"

namespace tcb {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// {count_key: judged, tp, fp, fn, tn, recall, precision[, accuracy]}: null
// when nothing was judged; a share null when its denominator is 0.
nlohmann::ordered_json confusion_json(const char* count_key, std::int64_t tp, std::int64_t fp, std::int64_t fn,
                                      std::int64_t tn, bool with_accuracy) {
  using Json = nlohmann::ordered_json;
  const std::int64_t judged = tp + fp + fn + tn;
  if (judged == 0) return nullptr;
  const auto share = [](std::int64_t a, std::int64_t n) { return n > 0 ? Json(static_cast<double>(a) / n) : Json(nullptr); };
  Json out = {{count_key, judged}, {"tp", tp}, {"fp", fp}, {"fn", fn}, {"tn", tn},
              {"recall", share(tp, tp + fn)}, {"precision", share(tp, tp + fp)}};
  if (with_accuracy) out["accuracy"] = share(tp + tn, judged);
  return out;
}

}  // namespace

OracleMeter::OracleMeter(const RunSetup& run) : m_oracle(run.oracle), m_overlap(run.overlap) {
  if (m_oracle.every > 0) m_triangle_pairs = std::make_unique<SurfaceTrianglePairs>(run.world);
}

std::vector<ColumnSpec> OracleMeter::columns() const {
  return {{"oracle_points", "points the oracle finds strictly inside another object"},
          {"recall", "share of the oracle's inside points the method holds"},
          {"precision", "share of the method's points (not on a boundary) the oracle finds inside"},
          {"depth_err_mean", "mean |method depth - true depth| over points both have (m)"},
          {"depth_err_max", "largest |method depth - true depth| (m)"},
          {"max_depth", "largest true penetration depth (m)"},
          {"overlap_volume", "exact overlap volume of all object pairs (m^3); empty when a pair is unmeasurable"},
          {"triangle_pairs", "intersecting surface triangle pairs (FCL)"},
          {"oracle_ms", "wall time of the oracle this step (ms); never handling time"}};
}

void OracleMeter::before_dynamics(StepContext& ctx) {
  std::optional<double> oracle_ms;
  if (m_oracle.due(ctx.step)) {
    const auto t0 = Clock::now();
    m_frame = compute_inside_oracle(ctx.world);
    const OracleComparison cmp = compare_with_oracle(ctx.handler.contacts(), m_frame);
    ctx.row.set("oracle_points", cmp.oracle_points);
    m_points_reported = ctx.handler.reports_points();
    if (cmp.recall && m_points_reported) ctx.row.set("recall", *cmp.recall);
    if (cmp.precision && m_points_reported) ctx.row.set("precision", *cmp.precision);
    if (cmp.depth_err_mean) ctx.row.set("depth_err_mean", *cmp.depth_err_mean);
    if (cmp.depth_err_max) ctx.row.set("depth_err_max", *cmp.depth_err_max);
    ctx.row.set("max_depth", cmp.max_depth_m);
    ctx.row.set("triangle_pairs", static_cast<std::int64_t>(m_triangle_pairs->find(ctx.world).size()));
    oracle_ms = ms_since(t0);
    judge_self_frames(ctx);
    if (m_points_reported) {
      if (cmp.recall) m_recalls.push_back(*cmp.recall);
      if (cmp.precision) m_precisions.push_back(*cmp.precision);
    } else {
      m_unmeasured.insert(
          "the method reports whole-object verdicts, not points: point recall, precision and depth errors do not "
          "apply to it (its measure is self_frames)");
    }
    m_depth_errors.insert(m_depth_errors.end(), cmp.depth_errors.begin(), cmp.depth_errors.end());
    m_self_depth_errors.insert(m_self_depth_errors.end(), cmp.self_depth_errors.begin(), cmp.self_depth_errors.end());
    m_self_points += cmp.self_points;
    m_self_points_with_depth += cmp.self_points_with_depth;
    m_max_depth = std::max(m_max_depth, cmp.max_depth_m);
    m_unmeasured.insert(m_frame.unmeasured.begin(), m_frame.unmeasured.end());
    ++m_oracle_steps;
    ctx.oracle = &m_frame;
  }
  if (m_overlap.due(ctx.step)) {
    const auto t0 = Clock::now();
    m_overlap_frame = compute_overlap_volumes(ctx.world);
    ++m_overlap_steps;
    if (m_overlap_frame.invalid.empty()) {
      ctx.row.set("overlap_volume", m_overlap_frame.total_m3);
      m_overlap_max = std::max(m_overlap_max.value_or(0.0), m_overlap_frame.total_m3);
    } else {
      ++m_overlap_invalid_steps;  // no value this step: never a silent 0
      m_unmeasured.insert(m_overlap_frame.invalid.begin(), m_overlap_frame.invalid.end());
    }
    oracle_ms = oracle_ms.value_or(0.0) + ms_since(t0);
    ctx.overlap = &m_overlap_frame;
  }
  if (oracle_ms) {
    ctx.row.set("oracle_ms", *oracle_ms);
    m_oracle_ms.push_back(*oracle_ms);
  }
}

void OracleMeter::judge_self_frames(const StepContext& ctx) {
  const std::vector<char> verdicts = ctx.handler.self_collision_verdicts(ctx.world);
  std::vector<char> truth(ctx.world.bodies.size(), 0);
  for (const OraclePoint& p : m_frame.inside)
    if (p.object == p.other) truth[static_cast<std::size_t>(p.object)] = 1;
  for (std::size_t b = 0; b < ctx.world.bodies.size(); ++b) {
    if (!self_collision_active(ctx.world.bodies[b])) continue;
    const bool said = b < verdicts.size() && verdicts[b];
    if (truth[b]) (said ? m_frames_tp : m_frames_fn)++;
    else (said ? m_frames_fp : m_frames_tn)++;
    if (ctx.handler.reports_points()) judge_self_parts(ctx, b);
  }
}

void OracleMeter::judge_self_parts(const StepContext& ctx, std::size_t b) {
  const TetMesh& mesh = *ctx.world.bodies[b].mesh;
  if (part_count(mesh) < 2) return;
  const std::size_t parts = part_count(mesh);
  // A vertex lies in the parts of its tets (one on a boundary between parts lies in both).
  const auto mark = [&](std::vector<char>& in, std::int32_t vertex) {
    for (const std::int32_t* t = mesh.vertex_tets.begin(vertex); t != mesh.vertex_tets.end(vertex); ++t) {
      const auto part = static_cast<std::size_t>(mesh.tet_part[static_cast<std::size_t>(*t)]);
      if (part < parts) in[part] = 1;
    }
  };
  std::vector<char> truth(parts, 0), said(parts, 0);
  for (const OraclePoint& p : m_frame.inside)
    if (p.object == p.other && static_cast<std::size_t>(p.object) == b) mark(truth, p.vertex);
  for (const Contact& c : ctx.handler.contacts())
    if (c.object == c.other && static_cast<std::size_t>(c.object) == b && !c.separated) mark(said, c.vertex);
  for (std::size_t k = 0; k < parts; ++k) {
    if (truth[k]) (said[k] ? m_parts_tp : m_parts_fn)++;
    else (said[k] ? m_parts_fp : m_parts_tn)++;
  }
}

void OracleMeter::summarize(Json& summary) const {
  // Null when the oracle did not run (or had nothing to compare), never 0.
  const auto min_of = [](const std::vector<double>& v) -> Json {
    return v.empty() ? Json(nullptr) : Json(*std::min_element(v.begin(), v.end()));
  };
  summary["recall_min"] = min_of(m_recalls);
  summary["recall_mean"] = m_recalls.empty() ? Json(nullptr) : Json(tcb::summarize(m_recalls).mean);
  summary["precision_min"] = min_of(m_precisions);
  if (m_depth_errors.empty()) {
    summary["depth_err"] = nullptr;
  } else {
    const Distribution e = tcb::summarize(m_depth_errors);
    summary["depth_err"] = {{"mean", e.mean}, {"rms", e.rms}, {"max", e.max}};
  }
  // Self-collision points: their depth error alone, and the share of them
  // the body's parts give a true depth (oracle/self_depth.hpp).
  if (m_self_depth_errors.empty()) {
    summary["self_depth_err"] = nullptr;
  } else {
    const Distribution e = tcb::summarize(m_self_depth_errors);
    summary["self_depth_err"] = {{"mean", e.mean}, {"rms", e.rms}, {"max", e.max}, {"count", e.count}};
  }
  summary["self_points"] = m_oracle_steps > 0 ? Json(m_self_points) : Json(nullptr);
  summary["self_points_with_depth"] = m_oracle_steps > 0 ? Json(m_self_points_with_depth) : Json(nullptr);
  summary["max_depth"] = m_oracle_steps > 0 ? Json(m_max_depth) : Json(nullptr);
  summary["oracle_steps"] = m_oracle_steps;
  summary["oracle_ms"] = distribution_json(m_oracle_ms);
  summary["overlap_volume_max"] = m_overlap_max ? Json(*m_overlap_max) : Json(nullptr);
  summary["overlap_steps"] = m_overlap_steps;
  summary["overlap_invalid_steps"] = m_overlap_invalid_steps;
  summary["self_frames"] = confusion_json("frames", m_frames_tp, m_frames_fp, m_frames_fn, m_frames_tn, true);
  summary["self_parts"] = confusion_json("judged", m_parts_tp, m_parts_fp, m_parts_fn, m_parts_tn, false);
  for (const std::string& reason : m_unmeasured) note_unmeasured(summary, reason);
}

}  // namespace tcb
