#pragma once
/// Whitespace-separated tokens of a text file with their line numbers, for the
/// line-oriented mesh formats (MEDIT, TetGen). `#` starts a comment running to
/// the end of the line. Every parse failure throws InputError naming the file
/// and the line of the offending token (or the last line at end of file).

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

namespace tcb {

class TokenReader {
 public:
  TokenReader(std::string file_name, std::string text);

  bool at_end();
  /// The next token without consuming it; empty at end of file.
  std::string_view peek();
  int peek_line();
  std::string_view next(const char* what);  // throws at end of file, naming `what`
  /// Parses the next token fully as a finite double / an integer in range.
  double next_double(const char* what);
  std::int64_t next_int(const char* what, std::int64_t min_value, std::int64_t max_value);
  /// A reference (a label some tools write as a real, `0.0`): an integer, or a
  /// finite real with an integral value in int64's range; anything else
  /// fails with the file and line.
  std::int64_t next_reference(const char* what);
  /// Consumes tokens up to the end of the current line (optional trailing fields).
  void skip_rest_of_line();

  /// How many entries of `min_chars` characters each the unread text could
  /// still hold, capped at `count`: what a header's count may reserve (a
  /// count larger than the file can hold must not drive an allocation; the
  /// read then fails at the end of the file, naming the line).
  std::size_t reservable(std::int64_t count, std::size_t min_chars) const {
    const std::size_t fit = (m_text.size() - m_pos) / std::max<std::size_t>(min_chars, 1);
    return count < 0 ? 0 : std::min(static_cast<std::size_t>(count), fit);
  }
  int line() const { return m_line; }
  [[noreturn]] void fail(int line, const std::string& problem) const;
  const std::string& file_name() const { return m_file_name; }

 private:
  void skip_space();
  std::string m_file_name;
  std::string m_text;
  std::size_t m_pos = 0;
  int m_line = 1;  // line of the character at m_pos
  int m_last_token_line = 1;  // where an error at end of file is reported
};

/// True when the token reads as a number (so a section of unknown layout can be
/// skipped up to the next keyword).
bool looks_numeric(std::string_view token);

}  // namespace tcb
