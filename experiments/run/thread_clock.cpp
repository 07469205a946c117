#include "experiments/run/thread_clock.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace tcb {

double thread_cpu_ms() {
  timespec ts{};
  return clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0 ? ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6 : 0.0;
}

std::int64_t thread_involuntary_switches() {
  rusage usage{};
  return getrusage(RUSAGE_THREAD, &usage) == 0 ? usage.ru_nivcsw : 0;
}

std::vector<int> allowed_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> out;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return out;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) out.push_back(c);
  return out;
}

std::string pin_current_thread(int cpu) {
  if (cpu < 0 || cpu >= CPU_SETSIZE) return "CPU " + std::to_string(cpu) + " does not exist";
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
  if (err == 0) return "";
  std::string allowed;
  for (const int c : allowed_cpus()) {
    if (!allowed.empty()) allowed += ',';
    allowed += std::to_string(c);
  }
  return "cannot pin to CPU " + std::to_string(cpu) + " (" + std::strerror(err) + "; allowed: " + allowed + ")";
}

ScopedPin::ScopedPin(int cpu) {
  cpu_set_t saved;
  CPU_ZERO(&saved);
  if (pthread_getaffinity_np(pthread_self(), sizeof saved, &saved) != 0) {
    m_error = "cannot read the thread's CPU affinity";
    return;
  }
  m_error = pin_current_thread(cpu);
  if (!m_error.empty()) return;
  const auto* bytes = reinterpret_cast<const unsigned char*>(&saved);
  m_saved.assign(bytes, bytes + sizeof saved);
}

ScopedPin::~ScopedPin() {
  if (m_saved.size() != sizeof(cpu_set_t)) return;
  cpu_set_t saved;
  std::memcpy(&saved, m_saved.data(), sizeof saved);
  pthread_setaffinity_np(pthread_self(), sizeof saved, &saved);
}

std::optional<int> pinned_cpu() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (pthread_getaffinity_np(pthread_self(), sizeof set, &set) != 0 || CPU_COUNT(&set) != 1) return std::nullopt;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) return c;
  return std::nullopt;
}

}  // namespace tcb
