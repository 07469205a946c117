#include "experiments/cli/progress_line.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace tcb {

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

ProgressLine::ProgressLine(std::string label, bool enabled)
    : m_label(std::move(label)), m_enabled(enabled), m_start(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::update(std::int64_t done, std::int64_t total) {
  if (!m_enabled) return;
  const auto now = std::chrono::steady_clock::now();
  if (m_drawn && done < total && now - m_last_draw < std::chrono::milliseconds(100)) return;
  m_last_draw = now;
  m_drawn = true;
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  const double fraction = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fputs(fmt::format("\r{} {}/{} {:3.0f}% {:.1f} s, ETA {:.1f} s   ", m_label, done, total, 100.0 * fraction,
                         elapsed, eta)
                 .c_str(),
             stderr);
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (m_enabled && m_drawn) std::fputs("\n", stderr);
  m_drawn = false;
}

}  // namespace tcb
