#pragma once
/// Which build and which machine made a result: recorded in every run.json so
/// a number can always be traced back.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace tcb {

/// git sha and dirty flag of the source at build time, compiler, flags, build
/// type, tcbench version.
nlohmann::ordered_json build_info();
/// CPU model, logical cores, host name, kernel.
nlohmann::ordered_json machine_info();
/// Current time as ISO 8601 UTC, e.g. 2026-11-21T23:30:00Z.
std::string utc_timestamp();
/// "tcbench 0.1.0 (abc1234, dirty)"
std::string version_line();
/// The source tree tcbench was built from: where it finds the committed
/// scenes, the paper's sweeps and the report script.
std::filesystem::path source_tree_dir();

}  // namespace tcb
