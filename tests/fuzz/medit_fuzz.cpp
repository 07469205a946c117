// Fuzz target: the MEDIT reader (sim/mesh/medit_io.hpp) on arbitrary bytes.
#include "sim/io/input_error.hpp"
#include "sim/mesh/medit_io.hpp"
#include "tests/fuzz/fuzz_input.hpp"

bool tcb::fuzz::read_input(const std::uint8_t* data, std::size_t size) {
  try {
    tcb::parse_medit("fuzz.mesh", tcb::fuzz::text_of(data, size));
  } catch (const tcb::InputError&) {
    return false;  // the documented answer to a malformed file
  }
  return true;
}
