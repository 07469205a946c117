// Fuzz target: scene files (experiments/scene/scene_file.hpp) with --set
// overrides. The input is a scene file, then optionally a line "---" and one
// override ("key=value") per line. Parsing only: building the world would
// load meshes, which the mesh targets fuzz.
#include "experiments/scene/scene_file.hpp"
#include "sim/io/input_error.hpp"
#include "tests/fuzz/fuzz_input.hpp"

bool tcb::fuzz::read_input(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> parts = tcb::fuzz::split_parts(tcb::fuzz::text_of(data, size));
  std::vector<std::string> overrides;
  for (std::size_t p = 1; p < parts.size(); ++p)
    for (std::string& line : tcb::fuzz::lines_of(parts[p])) overrides.push_back(std::move(line));
  try {
    tcb::parse_scene(parts[0], "fuzz.toml", overrides);
  } catch (const tcb::InputError&) {
    return false;  // the documented answer to a malformed file or override
  }
  return true;
}
