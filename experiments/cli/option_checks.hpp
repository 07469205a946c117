#pragma once
// CLI11 checks for the options' values, whose messages say what was wrong
// and what is allowed, where CLI11's own checks print DBL_MAX in full, let a
// NaN through a range, or say "not in range" of "1e3" for a whole number.

#include <CLI/CLI.hpp>

#include <cstdint>

namespace tcb::cli {

/// A whole number in [min, max], read from the text as typed (no detour
/// through double): "'1e20' is not a whole number; allowed: 1 .. 1099511627776".
CLI::Validator whole_number(std::int64_t min, std::int64_t max);

/// A finite decimal number in [min, max]; "nan" and "inf" are refused.
CLI::Validator decimal_number(double min, double max);

/// A path that is not empty: `--out ""` would otherwise write into the
/// current directory, or fail only after the work.
CLI::Validator non_empty_path();

}  // namespace tcb::cli
