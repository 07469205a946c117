// libFuzzer's entry point for every fuzz target (preset fuzz).
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tcb::fuzz::read_input(data, size);
  return 0;
}
