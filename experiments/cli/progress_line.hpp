#pragma once
/// A one-line progress display on standard error ("plates20 [none] 1200/2000
/// 60% 3.1 s, ETA 2.0 s"), redrawn at most ten times a second, and only when
/// standard error is a terminal: logs and CI output stay clean.

#include <chrono>
#include <cstdint>
#include <string>

namespace tcb {

class ProgressLine {
 public:
  ProgressLine(std::string label, bool enabled);
  ~ProgressLine();
  void update(std::int64_t done, std::int64_t total);
  void finish();

 private:
  std::string m_label;
  bool m_enabled;
  bool m_drawn = false;
  std::chrono::steady_clock::time_point m_start, m_last_draw;
};

/// Whether standard error is an interactive terminal.
bool stderr_is_terminal();

}  // namespace tcb
