#pragma once
/// The machine around a run: how busy the other processes kept the CPUs
/// (/proc/stat against our own process's CPU time), the load average
/// (/proc/loadavg) and the CPU frequency governor where the kernel exposes it
/// (/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor; absent in many
/// containers and VMs). Every reading is optional: unreadable is recorded as
/// unknown, never as quiet.

#include <cstdint>
#include <optional>
#include <string>

namespace tcb {

struct MachineSample {
  std::optional<double> busy_s, total_s;  ///< all CPUs together since boot (/proc/stat "cpu" line)
  double own_cpu_s = 0.0;                 ///< this process's CPU time (all its threads)
  double wall_s = 0.0;                    ///< steady clock
  std::optional<double> loadavg_1min;
};

MachineSample sample_machine();

inline constexpr double kMinLoadWindowS = 1.0;

/// The average number of CPUs the other processes kept busy between two
/// samples (busy time of the machine minus ours, over the wall time);
/// nullopt when /proc/stat was unreadable or less than kMinLoadWindowS
/// passed (its tick rounding would dominate). All of the machine's CPUs are
/// counted, also those this process may not use (a container on a larger
/// host sees its neighbours' load too).
std::optional<double> other_busy_cpus(const MachineSample& start, const MachineSample& end);

/// The machine's online CPUs (what /proc/stat's "cpu" line sums over); at least 1.
int online_cpus();

/// The governor of CPU 0 ("performance", "powersave", ...), when readable.
std::optional<std::string> cpu_governor();

/// Parses the "cpu" line of /proc/stat into busy and total seconds (USER_HZ
/// ticks: user nice system idle iowait irq softirq steal; guest time is
/// already inside user). nullopt for anything else.
std::optional<std::pair<double, double>> parse_proc_stat_cpu_line(const std::string& line, double ticks_per_s);

}  // namespace tcb
