#pragma once
/// A small CSV of numbers with a fixed header, as the driven objects' paths
/// use (world/trajectory.hpp, latent/latent_path.hpp): the first line must be
/// exactly `header`; every other non-empty line holds exactly as many
/// comma-separated finite numbers as the header has names; the first column
/// (time) increases strictly. A trailing CR is ignored. Anything else is an
/// InputError naming the file and the line, and `what` ("trajectory") says
/// which kind of file could not be opened.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace tcb {

/// The rows, each header-width long; at least one.
std::vector<std::vector<double>> read_numeric_csv(const std::filesystem::path& path, const std::string& header,
                                                  const std::string& what);

/// The value at time t of samples (times strictly increasing, at least one):
/// linear between samples, held before the first and after the last. For the
/// paths read from these files (positions, latent codes).
template <class Value>
Value sample_linear(const std::vector<double>& times, const std::vector<Value>& values, double t) {
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const std::size_t lo = hi - 1;
  const double w = (t - times[lo]) / (times[hi] - times[lo]);
  return (1.0 - w) * values[lo] + w * values[hi];
}

}  // namespace tcb
