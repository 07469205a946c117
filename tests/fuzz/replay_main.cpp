// Replays seeds through a fuzz target without libFuzzer, in every build:
// `fuzz_NAME [--min-accepted N] DIR_OR_FILE...` feeds each file (folders
// recursively) to the target's read_input once. A crash or an unexpected
// exception fails it, as it would fail the fuzzer; so do no inputs at all and
// fewer than N accepted ones (the valid seeds must still be read as valid,
// or the replay would only ever test the error paths).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_input.hpp"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::size_t min_accepted = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--min-accepted" && i + 1 < argc) {
      min_accepted = std::stoul(argv[++i]);
      continue;
    }
    const fs::path arg(argv[i]);
    if (fs::is_directory(arg)) {
      for (const auto& entry : fs::recursive_directory_iterator(arg))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (fs::is_regular_file(arg)) {
      files.push_back(arg);
    } else {
      std::fprintf(stderr, "%s: no such file or directory\n", argv[i]);
      return 2;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...: no inputs found\n", argv[0]);
    return 2;
  }
  std::size_t accepted = 0;
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    accepted += tcb::fuzz::read_input(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("replayed %zu inputs: %zu accepted, %zu refused with an InputError\n", files.size(), accepted,
              files.size() - accepted);
  if (accepted < min_accepted) {
    std::fprintf(stderr, "expected at least %zu accepted inputs\n", min_accepted);
    return 1;
  }
  return 0;
}
