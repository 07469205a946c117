#include "experiments/neural/code_labels.hpp"

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>

#include "experiments/neural/finger_labeller.hpp"
#include "method/neural/active_learning.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

CodeLabelCounts label_uniform_codes(const std::string& preset, std::int64_t count, std::uint64_t seed,
                                    const std::filesystem::path& out) {
  const auto finger = std::make_unique<SkinnedFinger>(finger_preset_option(preset));
  const int n = finger->latent_size();
  FingerLabeller labeller(*finger);
  std::ostringstream csv;
  for (int k = 0; k < n; ++k) csv << 'z' << k << ',';
  csv << "collides,pd_m\n";
  CodeLabelCounts counts;
  constexpr std::uint64_t kStream = 7;  // apart from the learning runs' streams
  for (std::int64_t i = 0; i < count; ++i) {
    const Eigen::VectorXd z = neural::uniform_code(n, seed, kStream, static_cast<std::uint64_t>(i));
    const SelfPenetration p = labeller.penetration(z);
    for (int k = 0; k < n; ++k) csv << fmt::format("{},", z[k]);
    csv << fmt::format("{},{}\n", int(p.penetrates), p.pd_m);
    ++counts.codes;
    counts.colliding += p.penetrates;
  }
  counts.label_seconds = labeller.seconds();
  write_file_atomically(out, csv.str());
  return counts;
}

}  // namespace tcb
