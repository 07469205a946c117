#pragma once
/// The runs of a results directory, and which of them are repeats of one
/// configuration. Shared by `tcbench check`, `tcbench compare` and the
/// sweep's configurations.csv, so all three see the same runs and group them
/// the same way.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tcb {

struct CollectedRun {
  std::string name;  ///< its path relative to the directory searched (its own name when it is that directory)
  std::filesystem::path dir;
  nlohmann::json record;  ///< run.json
};

/// DIR itself and every folder beneath it holding a complete run
/// (read_complete_run: a sweep's DIR/runs/*, reproduce's DIR/<sweep>/runs/*),
/// sorted by name. Reports and frames are not searched.
std::vector<CollectedRun> collect_runs(const std::filesystem::path& dir);

/// What makes runs repeats of one configuration: everything the run was told
/// except its seed (scene, method and its settings, budget label, response,
/// mesh order, steps requested, scene overrides). A run recorded before a field existed
/// gets that field's old meaning (tcbench.run/1: label = method, explicit response).
std::string configuration_key(const nlohmann::json& record);

/// The run's world.mesh_order ("file" or "curve"); "file" for a run recorded
/// before the field (they were all in the file's numbering).
std::string mesh_order_of(const nlohmann::json& record);

/// The same in words: "plates20 interruptible full-work/3 implicit 2000 steps [collision.cell_size=auto*2]".
std::string configuration_label(const nlohmann::json& record);

/// The summary metrics worth a line when configurations are summarized or
/// compared: time, work, accuracy and outcome figures of every meter family
/// (a run that lacks one simply has no value for it).
const std::vector<std::string>& headline_metrics();

/// Runs grouped by configuration_key, groups in order of their first run,
/// each group sorted by seed (then name).
std::vector<std::vector<const CollectedRun*>> group_repeats(const std::vector<CollectedRun>& runs);

}  // namespace tcb
