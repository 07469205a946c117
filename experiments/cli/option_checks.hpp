#pragma once
// CLI11 checks for the options' values, whose messages say what was wrong
// and what is allowed, where CLI11's own checks print DBL_MAX in full, let a
// NaN through a range, or say "not in range" of "1e3" for a whole number.

#include <CLI/CLI.hpp>

#include <cstdint>

namespace tcb::cli {

/// A whole number in [min, max], read from the text as typed (no detour
/// through double): "'1e20' is not a whole number; allowed: 1 .. 1099511627776".
/// It rewrites the text as the number it checked ("010" becomes "10", which
/// CLI11 would have read as octal 8), so give it with ->transform(), not
/// ->check(), whose validators see a copy.
CLI::Validator whole_number(std::int64_t min, std::int64_t max);

/// A finite number in [min, max], as strtod reads it; "nan", "inf", leading
/// blanks and values that over- or underflow are refused. Rewrites the text
/// as the double it checked (->transform(), as above).
CLI::Validator decimal_number(double min, double max);

/// A path that is not empty: `--out ""` would otherwise write into the
/// current directory, or fail only after the work.
CLI::Validator non_empty_path();

}  // namespace tcb::cli
