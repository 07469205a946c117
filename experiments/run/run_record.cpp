#include "experiments/run/run_record.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "sim/io/atomic_file.hpp"
#include "sim/mesh/curve_numbering.hpp"

namespace tcb {
namespace {

std::vector<ColumnSpec> with_step_columns(const std::vector<ColumnSpec>& columns) {
  std::vector<ColumnSpec> all = {{"step", "the step just completed (1-based)"},
                                 {"time_s", "simulated time after the step (s)"}};
  all.insert(all.end(), columns.begin(), columns.end());
  return all;
}

// What an earlier run left in `dir` that this one may not overwrite: a run
// without --record or --trajectory writes no frames, replay or trajectory,
// and those of the earlier run would then sit beside the new run.json, read
// as this run's by `--reference` and `tcbench view`. Only in a directory that
// holds a run's file (not a folder of the user's that --out happens to name),
// and only the files a run writes: run.json first, so the directory reads as
// incomplete until finish(); the frames one by one, their folder only once
// empty. A sweep's log.txt and a live session's probe_path.csv (an input of
// the runs that replay it) stay.
void remove_earlier_run(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const auto files = {"run.json", "steps.csv", "frames.pvd", "trajectory.bin", "replay.json", "replay.bin"};
  if (std::none_of(files.begin(), files.end(), [&](const char* name) { return fs::exists(dir / name); })) return;
  for (const char* name : files) fs::remove(dir / name);
  const fs::path frames = dir / "frames";
  if (!fs::is_directory(frames)) return;
  std::vector<fs::path> earlier;
  for (const fs::directory_entry& e : fs::directory_iterator(frames)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.rfind("frame_", 0) == 0 && e.path().extension() == ".vtu") earlier.push_back(e.path());
  }
  for (const fs::path& f : earlier) fs::remove(f);
  if (fs::is_empty(frames)) fs::remove(frames);
}

}  // namespace

RunRecord::RunRecord(const std::filesystem::path& dir, const std::vector<ColumnSpec>& columns, int frame_every,
                     const World& initial, int trajectory_every)
    : m_dir((std::filesystem::create_directories(dir), remove_earlier_run(dir), dir)),
      m_csv(dir / "steps.csv", with_step_columns(columns)),
      m_frame_every(frame_every) {
  if (m_frame_every > 0) write_frame(initial);
  if (trajectory_every > 0) m_trajectory = std::make_unique<TrajectoryWriter>(dir / "trajectory.bin", initial, trajectory_every);
}

void RunRecord::write_step(StepRow row, const World& world) {
  row.set("step", world.step_index);
  row.set("time_s", world.time_s);
  m_csv.write(row);
  if (m_frame_every > 0 && world.step_index % m_frame_every == 0) write_frame(world);
  if (m_trajectory) m_trajectory->write_step(world);
}

// All bodies of the world as one VTU frame, each body's points in its mesh
// file's numbering (sim/mesh/curve_numbering.hpp).
void RunRecord::write_frame(const World& world) {
  std::vector<Vec3> x, v;
  std::vector<Tet> tets;
  for (const Body& b : world.bodies) {
    const auto offset = static_cast<std::int32_t>(x.size());
    std::vector<Vec3> scratch;
    const std::vector<Vec3>& bx = in_file_order(*b.mesh, b.x_m, scratch);
    x.insert(x.end(), bx.begin(), bx.end());
    const std::vector<Vec3>& bv = in_file_order(*b.mesh, b.v_m_per_s, scratch);
    v.insert(v.end(), bv.begin(), bv.end());
    for (Tet t : b.mesh->tets) {
      for (auto& i : t) i = file_vertex(*b.mesh, i) + offset;
      tets.push_back(t);
    }
  }
  std::filesystem::create_directories(m_dir / "frames");
  const std::string name = fmt::format("frames/frame_{:06d}.vtu", world.step_index);
  write_vtu(m_dir / name, x, tets, {{"velocity_m_per_s", &v}});
  m_frames.push_back({world.time_s, name});
}

void RunRecord::finish(const nlohmann::ordered_json& run) {
  m_csv.commit();
  if (m_trajectory) m_trajectory->commit();
  if (!m_frames.empty()) write_pvd(m_dir / "frames.pvd", m_frames);
  write_file_atomically(m_dir / "run.json", run.dump(2) + "\n");
}

}  // namespace tcb
