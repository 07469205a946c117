#include "experiments/cli/report_runner.hpp"
#include "experiments/run/provenance.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <string>


namespace tcb::cli {

int run_program(const std::vector<std::string>& args) {
  std::cout.flush();
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

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
  const int status = run_program({python, script, results_dir.string()});
  return status == 128 || status < 0 ? 3 : status;
}

}  // namespace tcb::cli
