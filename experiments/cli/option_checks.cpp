#include "experiments/cli/whole_number.hpp"

#include <fmt/format.h>

#include <charconv>

namespace tcb::cli {

CLI::Validator whole_number(std::int64_t min, std::int64_t max) {
  const std::string allowed = fmt::format("allowed: {} .. {}", min, max);
  return CLI::Validator(
      [min, max, allowed](std::string& text) -> std::string {
        std::int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || ptr != end || ec == std::errc::invalid_argument)
          return fmt::format("'{}' is not a whole number; {}", text, allowed);
        if (ec == std::errc::result_out_of_range || value < min || value > max)
          return fmt::format("{} is out of range; {}", text, allowed);
        return {};
      },
      fmt::format("INT in [{} .. {}]", min, max));
}

}  // namespace tcb::cli
