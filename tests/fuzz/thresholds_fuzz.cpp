// Fuzz target: thresholds files (experiments/check/thresholds.hpp).
#include "experiments/check/thresholds.hpp"
#include "sim/io/input_error.hpp"
#include "tests/fuzz/fuzz_input.hpp"

bool tcb::fuzz::read_input(const std::uint8_t* data, std::size_t size) {
  try {
    tcb::parse_thresholds(tcb::fuzz::text_of(data, size), "fuzz.toml");
  } catch (const tcb::InputError&) {
    return false;  // the documented answer to a malformed file
  }
  return true;
}
