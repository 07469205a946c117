#include "experiments/run/provenance.hpp"

#include <sys/utsname.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <string_view>
#include <thread>

#include "experiments/run/build_info_generated.hpp"

namespace tcb {

nlohmann::ordered_json build_info() {
  nlohmann::ordered_json j;
  j["version"] = generated::kVersion;
  j["git_sha"] = generated::kGitSha;
  j["dirty"] = generated::kGitDirty;
  j["compiler"] = generated::kCompiler;
  j["flags"] = generated::kFlags;
  j["build_type"] = generated::kBuildType;
  return j;
}

nlohmann::ordered_json machine_info() {
  nlohmann::ordered_json j;
  std::string cpu = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  j["cpu"] = cpu;
  j["cores"] = std::thread::hardware_concurrency();
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  j["host"] = host;
  utsname u{};
  if (uname(&u) == 0) j["kernel"] = std::string(u.sysname) + " " + u.release;
  return j;
}

std::string utc_timestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

std::string version_line() {
  // Appended piece by piece: GCC 12 warned (-Warray-bounds, falsely) inside
  // std::string's move in the chain of operator+ this replaced.
  std::string line = "tcbench ";
  line += generated::kVersion;
  line += " (";
  line += std::string_view(generated::kGitSha).substr(0, 12);
  if (generated::kGitDirty) line += ", dirty";
  line += ", ";
  line += generated::kBuildType;
  line += ")";
  return line;
}

std::filesystem::path source_tree_dir() { return TCBENCH_SOURCE_DIR; }

}  // namespace tcb
