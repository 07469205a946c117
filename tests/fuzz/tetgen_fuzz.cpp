// Fuzz target: the TetGen reader (sim/mesh/tetgen_io.hpp). The input is a
// .node file, a line "---", and an .ele file.
#include "sim/io/input_error.hpp"
#include "sim/mesh/tetgen_io.hpp"
#include "tests/fuzz/fuzz_input.hpp"

bool tcb::fuzz::read_input(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> parts = tcb::fuzz::split_parts(tcb::fuzz::text_of(data, size));
  parts.resize(2);
  try {
    tcb::parse_tetgen("fuzz.node", std::move(parts[0]), "fuzz.ele", std::move(parts[1]));
  } catch (const tcb::InputError&) {
    return false;  // the documented answer to a malformed file
  }
  return true;
}
