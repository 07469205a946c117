#pragma once
/// The one error type for bad input (mesh files, scene files, command-line
/// values). Its message always names the file, the line where there is one,
/// and what is wrong, as `file:line: problem`; the CLI turns it into exit 2.

#include <stdexcept>
#include <string>

namespace tcb {

class InputError : public std::runtime_error {
 public:
  /// line = 0 when the problem has no line (a missing file, a whole-mesh check).
  InputError(std::string file, int line, const std::string& problem)
      : std::runtime_error(format(file, line, problem)), m_file(std::move(file)), m_line(line) {}

  const std::string& file() const { return m_file; }
  int line() const { return m_line; }

 private:
  static std::string format(const std::string& file, int line, const std::string& problem) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem;
  }
  std::string m_file;
  int m_line;
};

}  // namespace tcb
