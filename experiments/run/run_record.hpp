#pragma once
/// The files of one run in its directory (docs/contract.md "Results of one
/// run"): steps.csv (streamed to a temporary name, renamed at the end),
/// frames/*.vtu and frames.pvd for ParaView (--record N), trajectory.bin
/// (--trajectory N, results/trajectory_file.hpp), and run.json,
/// written last and atomically, so a run directory with a run.json is
/// complete.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <vector>

#include "experiments/results/steps_csv.hpp"
#include "experiments/results/trajectory_file.hpp"
#include "sim/mesh/vtu_writer.hpp"
#include "sim/world/world.hpp"

namespace tcb {

class RunRecord {
 public:
  /// Creates the directory, removes the files an earlier run wrote there
  /// (run.json first; see remove_earlier_run), and starts steps.csv with the columns step,
  /// time_s and then `columns`. A VTU frame is written every `frame_every`
  /// steps (0: none), the first one of the initial state right away.
  /// trajectory.bin gets the state every `trajectory_every` steps (0: no file).
  RunRecord(const std::filesystem::path& dir, const std::vector<ColumnSpec>& columns, int frame_every,
            const World& initial, int trajectory_every = 0);
  /// An empty row for the meters to fill.
  StepRow row() const { return m_csv.row(); }
  /// Appends the row for the step the world has just completed (its step and
  /// time_s filled in here), and a frame when one is due.
  void write_step(StepRow row, const World& world);
  /// Renames steps.csv into place, writes frames.pvd and run.json.
  void finish(const nlohmann::ordered_json& run);

 private:
  void write_frame(const World& world);

  std::filesystem::path m_dir;
  StepsCsv m_csv;
  int m_frame_every;
  std::vector<PvdFrame> m_frames;
  std::unique_ptr<TrajectoryWriter> m_trajectory;
};

}  // namespace tcb
