// Fuzz target: sweep files (experiments/sweep/sweep_plan.hpp), parsed and
// planned: every run's scene, method and settings checked, nothing run.
// Scenes named in the input are looked up in the committed scene folder.
#include "experiments/sweep/sweep_plan.hpp"
#include "sim/io/input_error.hpp"
#include "tests/fuzz/fuzz_input.hpp"

bool tcb::fuzz::read_input(const std::uint8_t* data, std::size_t size) {
  try {
    tcb::parse_sweep_plan(tcb::fuzz::text_of(data, size), "fuzz.toml");
  } catch (const tcb::InputError&) {
    return false;  // the documented answer to a malformed file
  }
  return true;
}
