#include "experiments/cli/report_runner.hpp"
#include "experiments/run/provenance.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <string>


namespace tcb::cli {

int run_report(const std::filesystem::path& results_dir) {
  const char* python = "/usr/bin/python3";
  const char* env = std::getenv("TCBENCH_REPORT_SCRIPT");
  const std::string script =
      env ? env : (source_tree_dir() / "report" / "make_report.py").string();
  if (!std::filesystem::exists(python)) {
    std::cerr << "tcbench: report: " << python << " not found (install python3-matplotlib: scripts/setup)\n";
    return 2;
  }
  if (!std::filesystem::exists(script)) {
    std::cerr << "tcbench: report: " << script << " not found (set TCBENCH_REPORT_SCRIPT)\n";
    return 2;
  }
  std::cout.flush();
  const pid_t pid = fork();
  if (pid < 0) return 3;
  if (pid == 0) {
    const std::string dir = results_dir.string();
    execl(python, python, script.c_str(), dir.c_str(), nullptr);
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 3;
}

}  // namespace tcb::cli
