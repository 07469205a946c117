#include "experiments/run/machine_load.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>

namespace tcb {

std::optional<std::pair<double, double>> parse_proc_stat_cpu_line(const std::string& line, double ticks_per_s) {
  std::istringstream in(line);
  std::string name;
  in >> name;
  if (name != "cpu" || !(ticks_per_s > 0.0)) return std::nullopt;
  double field[8] = {};
  for (double& f : field)
    if (!(in >> f)) return std::nullopt;
  const double idle = field[3] + field[4];  // idle + iowait
  double total = 0.0;
  for (const double f : field) total += f;
  return std::make_pair((total - idle) / ticks_per_s, total / ticks_per_s);
}

MachineSample sample_machine() {
  MachineSample s;
  std::ifstream stat("/proc/stat");
  std::string line;
  if (std::getline(stat, line))
    if (const auto parsed = parse_proc_stat_cpu_line(line, static_cast<double>(sysconf(_SC_CLK_TCK)))) {
      s.busy_s = parsed->first;
      s.total_s = parsed->second;
    }
  timespec ts{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) == 0) s.own_cpu_s = ts.tv_sec + ts.tv_nsec * 1e-9;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  std::ifstream loadavg("/proc/loadavg");
  double one = 0.0;
  if (loadavg >> one) s.loadavg_1min = one;
  return s;
}

std::optional<double> other_busy_cpus(const MachineSample& start, const MachineSample& end) {
  if (!start.busy_s || !end.busy_s) return std::nullopt;
  const double wall = end.wall_s - start.wall_s;
  // /proc/stat counts in ticks of 10 ms per CPU: over less than a second the
  // rounding alone could read as a quarter of a CPU busy.
  if (!(wall >= kMinLoadWindowS)) return std::nullopt;
  const double others = (*end.busy_s - *start.busy_s) - (end.own_cpu_s - start.own_cpu_s);
  return std::max(0.0, others / wall);  // tick granularity can make a quiet machine read slightly below 0
}

int online_cpus() { return static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN))); }

std::optional<std::string> cpu_governor() {
  std::ifstream in("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor");
  std::string g;
  if (in >> g) return g;
  return std::nullopt;
}

}  // namespace tcb
