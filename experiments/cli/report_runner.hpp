#pragma once
// Runs report/make_report.py on a results directory with Debian's Python
// (/usr/bin/python3: the python3 first on PATH may lack matplotlib). The
// script is found at TCBENCH_REPORT_SCRIPT when set, else in the source tree
// tcbench was built from. Returns the script's exit status (2 when it cannot
// be started).

#include <filesystem>
#include <string>
#include <vector>

namespace tcb::cli {

/// Runs args[0] (looked up on PATH) with the rest as its arguments, with this
/// process's stdout and stderr, and waits: its exit status; -1 when no process
/// could be made, 127 when the program could not be started, 128 when it died
/// of a signal.
int run_program(const std::vector<std::string>& args);

int run_report(const std::filesystem::path& results_dir);

}  // namespace tcb::cli
