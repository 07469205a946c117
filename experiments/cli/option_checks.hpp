#pragma once
// A CLI11 check for options that take a whole number in a range: it reads
// the text as typed (no detour through double), and its message says what
// was wrong and what is allowed ("'1e20' is not a whole number; allowed:
// 1 .. 1099511627776"), where CLI11's own checks print DBL_MAX in full.

#include <CLI/CLI.hpp>

#include <cstdint>

namespace tcb::cli {

CLI::Validator whole_number(std::int64_t min, std::int64_t max);

}  // namespace tcb::cli
