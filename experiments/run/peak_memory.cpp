#include "experiments/run/peak_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace tcb {

std::optional<std::uint64_t> peak_resident_bytes(const std::filesystem::path& status_file) {
  std::ifstream in(status_file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream fields(line.substr(6));
    std::uint64_t kib = 0;
    std::string unit;
    if (!(fields >> kib >> unit) || unit != "kB") return std::nullopt;
    return kib * 1024;
  }
  return std::nullopt;
}

std::optional<std::uint64_t> peak_resident_bytes() { return peak_resident_bytes("/proc/self/status"); }

}  // namespace tcb
