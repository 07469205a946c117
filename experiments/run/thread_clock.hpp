#pragma once
/// What the calling thread itself spent, for telling a method's overshoot from
/// the operating system's: its CPU time and its involuntary context switches
/// (the scheduler took the CPU away). Linux: CLOCK_THREAD_CPUTIME_ID and
/// getrusage(RUSAGE_THREAD). The handler runs on the run loop's thread (no
/// worker threads), so the run loop's thread is the handling thread.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tcb {

/// The thread's CPU time (ms; read inside the handling interval) and its
/// involuntary switches so far (getrusage: read around the interval, so its
/// cost stays out of handling_ms).
double thread_cpu_ms();
std::int64_t thread_involuntary_switches();

/// The CPUs this process may run on (sched_getaffinity), ascending.
std::vector<int> allowed_cpus();

/// Pins the calling thread to `cpu`. Empty on success, else why not (the CPU
/// does not exist or is not allowed here, or the kernel refused).
std::string pin_current_thread(int cpu);

/// The CPU the calling thread is pinned to: its affinity holds exactly one
/// CPU; nullopt otherwise.
std::optional<int> pinned_cpu();

/// Pins the calling thread for its lifetime and gives the thread its former
/// affinity back when destroyed (a run pins; the next run in the same
/// process must not inherit it). error() says why pinning failed (then
/// nothing changed).
class ScopedPin {
 public:
  explicit ScopedPin(int cpu);
  ~ScopedPin();
  ScopedPin(const ScopedPin&) = delete;
  ScopedPin& operator=(const ScopedPin&) = delete;
  const std::string& error() const { return m_error; }

 private:
  std::vector<unsigned char> m_saved;  // the former cpu_set_t, bytewise
  std::string m_error;
};

}  // namespace tcb
