#pragma once
/// `tcbench neural gen`: a labelled data set for users who train their own
/// detector. `count` codes drawn uniformly from [-1, 1]^n (counter-based:
/// method/neural/active_learning.hpp's uniform_code, stream 7 under `seed`, so
/// the same seed gives the same codes), each labelled exactly by the oracle
/// (finger_labeller.hpp). Writes `out` (CSV, atomically):
///   z0, ..., z{n-1}, collides, pd_m
/// pd_m the largest true vertex depth (m; 0 when collision-free;
/// oracle/self_penetration.hpp).

#include <cstdint>
#include <filesystem>
#include <string>

namespace tcb {

struct CodeLabelCounts {
  std::int64_t codes = 0, colliding = 0;
  double label_seconds = 0.0;
};

/// InputError naming --preset for an unknown preset.
CodeLabelCounts label_uniform_codes(const std::string& preset, std::int64_t count, std::uint64_t seed,
                                    const std::filesystem::path& out);

}  // namespace tcb
