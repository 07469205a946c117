#include "experiments/cli/option_checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

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
        text = std::to_string(value);  // what CLI11 converts: it would read "010" as octal 8
        return {};
      },
      fmt::format("INT in [{} .. {}]", min, max));
}

CLI::Validator decimal_number(double min, double max) {
  const std::string allowed = fmt::format("allowed: {} .. {}", min, max);
  return CLI::Validator(
      [min, max, allowed](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
        if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])) || end != text.c_str() + text.size() ||
            !std::isfinite(value))
          return fmt::format("'{}' is not a finite number; {}", text, allowed);
        if (errno == ERANGE || value < min || value > max)
          return fmt::format("{} is out of range; {}", text, allowed);
        text = fmt::format("{:.17g}", value);  // what CLI11 converts (through long double otherwise)
        return {};
      },
      fmt::format("NUMBER in [{} .. {}]", min, max));
}

CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string { return text.empty() ? "is empty; name a file or directory" : ""; },
      "");
}

}  // namespace tcb::cli
