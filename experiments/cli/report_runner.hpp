#pragma once
// Runs report/make_report.py on a results directory with Debian's Python
// (/usr/bin/python3: the python3 first on PATH may lack matplotlib). The
// script is found at TCBENCH_REPORT_SCRIPT when set, else in the source tree
// tcbench was built from. Returns the script's exit status (2 when it cannot
// be started).

#include <filesystem>

namespace tcb::cli {

int run_report(const std::filesystem::path& results_dir);

}  // namespace tcb::cli
