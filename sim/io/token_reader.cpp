#include "sim/io/token_reader.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "sim/io/input_error.hpp"

namespace tcb {

TokenReader::TokenReader(std::string file_name, std::string text)
    : m_file_name(std::move(file_name)), m_text(std::move(text)) {}

void TokenReader::skip_space() {
  while (m_pos < m_text.size()) {
    const char c = m_text[m_pos];
    if (c == '\n') {
      ++m_line;
      ++m_pos;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++m_pos;
    } else if (c == '#') {
      while (m_pos < m_text.size() && m_text[m_pos] != '\n') ++m_pos;
    } else {
      return;
    }
  }
}

bool TokenReader::at_end() {
  skip_space();
  return m_pos >= m_text.size();
}

std::string_view TokenReader::peek() {
  skip_space();
  std::size_t end = m_pos;
  while (end < m_text.size() && !std::isspace(static_cast<unsigned char>(m_text[end])) &&
         m_text[end] != '#')
    ++end;
  return std::string_view(m_text).substr(m_pos, end - m_pos);
}

int TokenReader::peek_line() {
  skip_space();
  return m_line;
}

std::string_view TokenReader::next(const char* what) {
  const std::string_view token = peek();
  if (token.empty()) fail(m_last_token_line, std::string("file ends where ") + what + " was expected");
  m_pos += token.size();
  m_last_token_line = m_line;
  return token;
}

void TokenReader::skip_rest_of_line() {
  while (m_pos < m_text.size() && m_text[m_pos] != '\n') ++m_pos;
}

double TokenReader::next_double(const char* what) {
  const int line = peek_line();
  const std::string_view token = next(what);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    fail(line, std::string("expected ") + what + " (a number), found '" + std::string(token) + "'");
  if (!std::isfinite(value))
    fail(line, std::string(what) + " is not finite ('" + std::string(token) + "')");
  return value;
}

std::int64_t TokenReader::next_int(const char* what, std::int64_t min_value,
                                   std::int64_t max_value) {
  const int line = peek_line();
  const std::string_view token = next(what);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    fail(line, std::string("expected ") + what + " (an integer), found '" + std::string(token) + "'");
  if (value < min_value || value > max_value)
    fail(line, std::string(what) + " " + std::to_string(value) + " is out of range [" +
                   std::to_string(min_value) + ", " + std::to_string(max_value) + "]");
  return value;
}

std::int64_t TokenReader::next_reference(const char* what) {
  const int line = peek_line();
  const std::string_view token = next(what);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc() && end == token.data() + token.size()) return value;
  double real = 0.0;
  const auto [real_end, real_ec] = std::from_chars(token.data(), token.data() + token.size(), real);
  // 2^63 is the first double beyond int64: below it every integral double converts exactly.
  if (real_ec == std::errc() && real_end == token.data() + token.size() && std::isfinite(real) &&
      real == std::floor(real) && real >= -9223372036854775808.0 && real < 9223372036854775808.0)
    return static_cast<std::int64_t>(real);
  fail(line, std::string("expected ") + what + " (an integer, or a real with an integral value such as 0.0), found '" +
                 std::string(token) + "'");
  return 0;
}

void TokenReader::fail(int line, const std::string& problem) const {
  throw InputError(m_file_name, line, problem);
}

bool looks_numeric(std::string_view token) {
  if (token.empty()) return false;
  const char c = token[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

}  // namespace tcb
