#include "experiments/run/peak_memory.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

using namespace tcb;

namespace {

// VmRSS (bytes) of this process now: what the high-water mark must reach.
std::uint64_t resident_now() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

}  // namespace

TEST_CASE("peak resident memory covers what the process touches", "[peak_memory]") {
  REQUIRE(peak_resident_bytes().has_value());
  const std::uint64_t before = resident_now();
  REQUIRE(before > 0);
  constexpr std::size_t kBytes = std::size_t(96) << 20;
  const std::unique_ptr<char[]> block(new char[kBytes]);
  std::memset(block.get(), 1, kBytes);  // touched, so resident
  const std::uint64_t holding = resident_now();
  REQUIRE(holding + (std::size_t(8) << 20) >= before + kBytes);  // the block is resident (the test's premise)
  // The high-water mark is at least what is resident now, whatever earlier
  // tests in this process peaked at.
  const auto peak = peak_resident_bytes();
  REQUIRE(peak.has_value());
  CHECK(*peak >= holding);
  volatile char sink = block[kBytes / 2];
  (void)sink;
}

TEST_CASE("peak resident memory reads VmHWM in KiB and refuses what it cannot parse", "[peak_memory]") {
  const auto dir = std::filesystem::temp_directory_path() / "tcbench_peak_memory_test";
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* text) {
    std::ofstream(dir / "status") << text;
    return peak_resident_bytes(dir / "status");
  };
  CHECK(write("Name:\ttcbench\nVmPeak:\t  999 kB\nVmHWM:\t    2048 kB\nVmRSS:\t 100 kB\n") == std::uint64_t(2048) * 1024);
  CHECK_FALSE(write("Name:\ttcbench\nVmRSS:\t 100 kB\n").has_value());
  CHECK_FALSE(write("VmHWM:\t lots\n").has_value());
  CHECK_FALSE(write("VmHWM:\t 12 MB\n").has_value());
  CHECK_FALSE(peak_resident_bytes(dir / "missing").has_value());
  std::filesystem::remove_all(dir);
}
