#pragma once
/// The state `tcbench live` shares between its simulation thread and the
/// server's threads: where the mouse wants the probe, the latest frame for the
/// page, the path the probe followed (saved as a trajectory CSV that
/// `tcbench run` replays: seed 001's scene builder), and whether to stop.
/// Every member function is thread-safe.

#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "experiments/metrics/meter.hpp"
#include "sim/world/world.hpp"

namespace tcb {

/// One probe target from the page: the body of POST /live/probe, a JSON
/// object {"x": m, "y": m, "z": m} of finite numbers. Returns the position, or
/// the reason it was refused (for a 400 answer).
struct ProbeMessage {
  std::optional<Vec3> position_m;
  std::string error;
};
ProbeMessage parse_probe_message(const std::string& body);

/// The scene as the page draws it, once: surface triangles (indices into the
/// surface vertices of all bodies in order), each surface vertex's body, the
/// body names, which body the mouse drives, and the step's length.
std::string live_scene_json(const World& world, std::size_t probe_body, double dt_s);

class LiveSession {
 public:
  /// `probe_body`: the driven body the mouse moves, starting where the scene
  /// put it (its trajectory's first position, or its placement).
  LiveSession(const World& world, std::size_t probe_body, double dt_s, double budget_ms);

  /// The mouse: a new target for the probe. Refused (false) beyond
  /// `reach_m` of where it started, so a runaway drag cannot fling it away.
  bool set_target(const Vec3& target_m);
  Vec3 target() const;

  /// Simulation thread, before each step: points the probe's trajectory at
  /// the current target (a one-sample path: it holds there), and records the
  /// target at the step's end time for the saved path.
  void drive(World& world);
  /// Simulation thread, after each step: keeps the loop's rate and overshoot,
  /// publishes a frame on the first step and then at most 30 a second of wall
  /// time, and sleeps so that simulated time does not run ahead of the wall
  /// clock. Returns false once stop() was called. A frame is JSON: step,
  /// time_s, positions (float x 3 per surface vertex, the scene's order),
  /// contacts ([x, y, z, depth_m, dx, dy, dz, force source (0 computed,
  /// 1 held, 2 extrapolated, 3 tracked, 255 none)] per colliding point),
  /// probe_centre_m, probe_target_m, probe_force_n, handling_ms, budget_ms
  /// (null without), rate_hz (steps in the last second of wall time),
  /// target_rate_hz (1/dt), overshoot_max_ms (the largest handling time above
  /// the budget in the last second), over_budget_share (of all steps).
  bool after_step(const StepContext& ctx);

  /// The newest frame after `seen` (its sequence number), waiting up to
  /// `timeout_s`; nullopt when none came or the session stopped.
  std::optional<std::pair<std::uint64_t, std::string>> next_frame(std::uint64_t seen, double timeout_s);

  void stop();
  bool stopped() const;

  /// The probe's path so far as `time_s,x_m,y_m,z_m` rows (1 per step),
  /// written atomically to `path`.
  void save_path(const std::filesystem::path& path) const;
  const std::string& scene_json() const { return m_scene; }
  double reach_m() const { return m_reach_m; }

 private:
  std::string frame_json(const StepContext& ctx) const;

  mutable std::mutex m_mutex;
  std::condition_variable m_changed;
  std::size_t m_probe;
  double m_dt_s, m_budget_ms;
  Vec3 m_start_m, m_target_m;
  std::shared_ptr<Trajectory> m_hold;  ///< the probe's one-sample path (simulation thread only)
  double m_reach_m;
  std::vector<std::uint32_t> m_surface_body, m_surface_vertex;
  std::string m_scene;
  std::vector<double> m_path_time_s;
  std::vector<Vec3> m_path_m;
  // The loop's pace, over the last second of wall time.
  double m_wall_start_s = -1.0, m_last_frame_s = -1.0;
  std::vector<double> m_step_wall_s;  // wall time of recent steps (last second)
  double m_overshoot_max_ms = 0.0;    // largest handling time above the budget in the last second
  std::vector<std::pair<double, double>> m_overshoots;  // (wall s, ms above the budget)
  std::int64_t m_over_budget_steps = 0, m_steps = 0;
  std::uint64_t m_sequence = 0;
  std::string m_frame;
  bool m_stopped = false;
};

}  // namespace tcb
