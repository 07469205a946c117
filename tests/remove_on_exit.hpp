#pragma once
/// For tests that write into the temporary directory: removes `path` (a file
/// or a directory tree) when the scope ends, whether the test case passed or
/// a failed REQUIRE is unwinding through it. Never throws.

#include <filesystem>
#include <system_error>
#include <utility>

namespace tcb::test {

struct RemoveOnExit {
  explicit RemoveOnExit(std::filesystem::path p) : path(std::move(p)) {}
  RemoveOnExit(const RemoveOnExit&) = delete;
  RemoveOnExit& operator=(const RemoveOnExit&) = delete;
  ~RemoveOnExit() {
    std::error_code ignored;  // a destructor must not throw, least of all while unwinding
    std::filesystem::remove_all(path, ignored);
  }
  std::filesystem::path path;
};

}  // namespace tcb::test
