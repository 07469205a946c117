#include "experiments/metrics/force_error.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace tcb {
namespace {

using PointKey = std::pair<std::int32_t, std::int32_t>;

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

}  // namespace

const char* force_source_name(ForceSource source) {
  switch (source) {
    case ForceSource::Computed: return "computed";
    case ForceSource::Held: return "held";
    case ForceSource::Extrapolated: return "extrapolated";
    case ForceSource::Tracked: return "tracked";
  }
  return "?";
}

ForceError compare_forces(const ForceField& applied, const std::vector<ForcePoint>& applied_points,
                          const ForceField& reference, const std::vector<ForcePoint>& reference_points) {
  if (applied.size() != reference.size()) throw std::invalid_argument("compare_forces: different body counts");
  ForceError out;
  double difference2 = 0.0, reference2 = 0.0;
  for (std::size_t b = 0; b < applied.size(); ++b) {
    if (applied[b].size() != reference[b].size())
      throw std::invalid_argument("compare_forces: different vertex counts");
    for (std::size_t v = 0; v < applied[b].size(); ++v) {
      difference2 += (applied[b][v] - reference[b][v]).squaredNorm();
      reference2 += reference[b][v].squaredNorm();
    }
  }
  out.reference_norm_n = std::sqrt(reference2);
  if (reference2 > 0.0) out.relative_l2 = std::sqrt(difference2 / reference2);
  else if (difference2 == 0.0) out.relative_l2 = 0.0;

  std::map<PointKey, ForceSource> method;
  for (const ForcePoint& p : applied_points) method.emplace(PointKey{p.object, p.vertex}, p.source);
  std::map<PointKey, bool> exact;  // reference point -> the method gave it a force
  for (const ForcePoint& p : reference_points) exact.emplace(PointKey{p.object, p.vertex}, false);
  out.applied_points = static_cast<std::int64_t>(method.size());
  out.reference_points = static_cast<std::int64_t>(exact.size());

  for (const auto& [key, source] : method) {
    SourceForceError& s = out.by_source[static_cast<std::size_t>(source)];
    ++s.points;
    const Vec3& fm = applied[key.first][key.second];
    const Vec3& fr = reference[key.first][key.second];
    s.squared_error_n2 += (fm - fr).squaredNorm();
    const auto match = exact.find(key);
    if (match == exact.end()) {
      ++s.ghosts;
      ++out.ghosts;
      continue;
    }
    match->second = true;
    if (fm.squaredNorm() > 0.0 && fr.squaredNorm() > 0.0) {
      const double a = angle_deg(fm, fr);
      s.angle_deg.push_back(a);
      out.angle_deg.push_back(a);
    }
  }
  for (const auto& [key, served] : exact) out.missed += served ? 0 : 1;
  return out;
}

}  // namespace tcb
