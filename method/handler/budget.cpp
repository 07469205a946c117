#include "method/handler/budget.hpp"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

namespace tcb {

ClockMs steady_clock_ms() {
  return [] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
}

std::optional<double> parse_budget_number(const std::string& text) {
  // Plain decimals only: no sign, exponent, blanks or "inf", so a label means
  // one thing and is written one way ("work:20000", never "work:2e4").
  if (text.empty() || text.find_first_not_of("0123456789.") != std::string::npos) return std::nullopt;
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v) && v >= 0.0) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::string plain_decimal(double value) {
  std::string text = fmt::format("{}", value);  // shortest round trip
  if (text.find_first_of("eE") == std::string::npos) return text;
  text = fmt::format("{:.17f}", value);  // tiny or huge: positional digits instead of an exponent
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

std::optional<BudgetSpec> BudgetSpec::parse(const std::string& text) {
  if (text == "none") return BudgetSpec{};
  if (text.rfind("ms:", 0) == 0) {
    const auto v = parse_budget_number(text.substr(3));
    if (v) return BudgetSpec{BudgetKind::WallMs, *v};
  } else if (text.rfind("work:", 0) == 0) {
    // Digits only, read as an integer (never through a double, which would
    // round 2^53 + 1 to 2^53), up to 2^53: the integers the spec's double
    // holds exactly.
    const std::string digits = text.substr(5);
    std::uint64_t units = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), units);
    if (!digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos && error == std::errc() &&
        end == digits.data() + digits.size() && static_cast<double>(units) <= kMaxWorkBudget &&
        units <= static_cast<std::uint64_t>(kMaxWorkBudget))
      return BudgetSpec{BudgetKind::Work, static_cast<double>(units)};
  }
  return std::nullopt;
}

std::string BudgetSpec::label() const {
  switch (kind) {
    case BudgetKind::WallMs: return "ms:" + plain_decimal(value);
    case BudgetKind::Work: return fmt::format("work:{}", static_cast<std::uint64_t>(value));
    case BudgetKind::None: break;
  }
  return "none";
}

std::string BudgetSpec::kind_name() const {
  switch (kind) {
    case BudgetKind::WallMs: return "wall_ms";
    case BudgetKind::Work: return "work";
    case BudgetKind::None: break;
  }
  return "none";
}

Budget BudgetSpec::start() const {
  switch (kind) {
    case BudgetKind::WallMs: return Budget::wall_ms(value);
    case BudgetKind::Work: return Budget::work_units(static_cast<std::uint64_t>(value));
    case BudgetKind::None: break;
  }
  return Budget::unlimited();
}

}  // namespace tcb
