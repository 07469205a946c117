#pragma once
/// Force extrapolation for points whose collision cycle is incomplete
/// (the paper, "response force extrapolation"; METHOD.md s.5).
///
/// A point keeps its last two depth-based forces f1 (newest) and f2, the step
/// f1 was computed in, and n, the length in steps of the cycle that produced
/// f1. At a later step s the extrapolated force is
///   f(s) = f1 + (s - s1) df,   df = (f1 - f2) / n,
/// i.e. df is added once per step. Only depth-based forces enter the history:
/// nothing is ever extrapolated from an extrapolated force. With a single
/// depth-based force (f2 unknown) df = 0 and f1 is held. When the force is
/// decreasing (|f1| < |f2|) and the next value would point against f1, the
/// force is set to zero and stays zero until the next depth-based force.
/// Units: N, steps.

#include <cstdint>
#include <optional>

#include "method/handler/contact.hpp"

namespace tcb {

struct ForceHistory {
  Vec3 f1 = Vec3::Zero(), f2 = Vec3::Zero();
  bool has_f1 = false, has_f2 = false;
  std::int64_t step_f1 = 0;   ///< step whose cycle produced f1
  std::int64_t cycle_steps = 1;  ///< n: length of that cycle, >= 1
  Contact contact;            ///< where f1 acted (tet, barycentric weights) for the reaction
  bool stopped = false;       ///< clamped to zero until the next depth-based force
};

/// Records a new depth-based force computed at `step` by a cycle of
/// `cycle_steps` steps; the previous f1 becomes f2.
void record_depth_force(ForceHistory& history, const Contact& contact, std::int64_t step, std::int64_t cycle_steps);

/// The extrapolated force at `step` (> step_f1), updating the stop flag.
Vec3 extrapolated_force(ForceHistory& history, std::int64_t step);

}  // namespace tcb
