// Shards of one sweep write summary.csv one at a time.
#include "experiments/sweep/directory_lock.hpp"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

using namespace tcb;
namespace fs = std::filesystem;

TEST_CASE("directory lock: a second process waits until the first releases it", "[sweep][fast]") {
  const fs::path dir = fs::temp_directory_path() / ("tcbench_lock_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path marker = dir / "child_has_lock";
  std::optional<DirectoryLock> held(std::in_place, dir);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    {
      const DirectoryLock lock(dir);  // blocks while the parent holds it
      std::ofstream(marker) << "x";
    }
    _exit(0);
  }
  // The child has had ample time to take an unheld lock; it must still wait.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  CHECK_FALSE(fs::exists(marker));
  held.reset();
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  CHECK(WIFEXITED(status));
  CHECK(fs::exists(marker));
  fs::remove_all(dir);
}

TEST_CASE("directory lock: a missing directory is a clear error", "[sweep][fast]") {
  CHECK_THROWS_WITH(DirectoryLock("/nonexistent/tcbench/dir"), Catch::Contains("cannot open /nonexistent/tcbench/dir/.summary.lock"));
}
