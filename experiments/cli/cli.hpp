#pragma once
/// The tcbench command line (docs/contract.md "Commands"), callable in-process so
/// tests can check exit codes and files.
/// Exit status: 0 success; 1 a run went unstable (its files are written);
/// 2 bad input (usage, a malformed or inconsistent file: the message names the
/// file and line); 3 a system failure (results could not be written).

namespace tcb {

int run_cli(int argc, const char* const* argv);

}  // namespace tcb
