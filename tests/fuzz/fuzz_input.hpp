#pragma once
// What every fuzz target shares. A target (NAME_fuzz.cpp) defines
// read_input(): it reads the bytes as its reader's input and answers whether
// the reader accepted them. The one rule of the readers under test: malformed
// input is an InputError (file, line, problem; exit status 2 in the CLI),
// which read_input turns into false. Any other exception escapes and aborts:
// libFuzzer (libfuzzer_entry.cpp) reports a crash, and the seed replay
// (replay_main.cpp, ctest "fuzz seeds: NAME") fails.

#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tcb::fuzz {

/// The target's reader on one input: true when accepted, false on InputError.
bool read_input(const std::uint8_t* data, std::size_t size);

inline std::string text_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// The input cut at every line that is exactly `separator` ("---"): a scene
/// and its overrides, or a .node and an .ele file, in one corpus entry.
inline std::vector<std::string> split_parts(const std::string& text, std::string_view separator = "---") {
  std::vector<std::string> parts(1);
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line(text.data() + start, end - start);
    if (line == separator)
      parts.emplace_back();
    else
      parts.back().append(text, start, end - start + (end < text.size() ? 1 : 0));
    start = end + 1;
  }
  return parts;
}

/// The lines of `text`, without their line ends; empty lines dropped.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end > start) lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

}  // namespace tcb::fuzz
