// tcbench live without a browser: the probe messages the server accepts, and
// a live session driving haptic_probe's probe through run_scene's hooks (the
// probe goes where the mouse puts it, the run stops when asked with its files
// complete, and the saved path replays as a trajectory).
#include "experiments/view/live_session.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <memory>

#include <nlohmann/json.hpp>

#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/world/trajectory.hpp"

using namespace tcb;
namespace fs = std::filesystem;

TEST_CASE("live: a probe message is three finite coordinates and nothing else", "[live]") {
  const ProbeMessage ok = parse_probe_message(R"({"x": 0.1, "y": -2, "z": 3e-3})");
  REQUIRE(ok.position_m);
  CHECK(*ok.position_m == Vec3(0.1, -2, 3e-3));
  CHECK(ok.error.empty());
  for (const char* bad : {"", "not json", "[1,2,3]", R"({"x":1,"y":2})", R"({"x":1,"y":"2","z":3})",
                          R"({"x":1,"y":2,"z":3,"w":4})", R"({"x":1,"y":2,"z":null})", R"({"x":1e999,"y":2,"z":3})"}) {
    INFO(bad);
    const ProbeMessage m = parse_probe_message(bad);
    CHECK_FALSE(m.position_m);
    CHECK_FALSE(m.error.empty());
  }
}

TEST_CASE("live: the mouse's target moves the probe, the run stops when asked, the path reads back as a trajectory", "[live]") {
  const SceneDesc scene = load_scene_file(resolve_scene("haptic_probe", default_scene_dirs()));
  const fs::path dir = fs::temp_directory_path() / ("tcbench_live_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  RunOptions options;
  options.out_dir = dir;
  options.steps = 1000;
  std::unique_ptr<LiveSession> session;
  Vec3 start, centre_start, centre_end;
  const auto centre = [](const Body& b) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : b.x_m) c += x;
    return Vec3(c / static_cast<double>(b.x_m.size()));
  };
  std::size_t probe = 0;
  options.before_step = [&](World& world) {
    if (!session) {
      while (world.bodies[probe].name != "probe") ++probe;
      session = std::make_unique<LiveSession>(world, probe, scene.world.dt_s, 0.0);
      start = session->target();
      centre_start = centre(world.bodies[probe]);
      CHECK_FALSE(session->set_target(start + Vec3(0, 0, 10.0 * session->reach_m())));  // beyond reach: refused
      CHECK(session->set_target(start + Vec3(0.01, 0.02, -0.03)));
    }
    session->drive(world);
  };
  std::int64_t steps = 0;
  options.after_step = [&](const StepContext& ctx) {
    centre_end = centre(ctx.world.bodies[probe]);
    if (++steps == 20) session->stop();  // Ctrl-C, as the server's signal thread would
    return session->after_step(ctx);
  };
  const RunOutcome outcome = run_scene(scene, options);
  CHECK(outcome.status == "ok");
  CHECK(outcome.steps_done == 20);  // the step that saw stop() was the last
  const auto run = nlohmann::json::parse(read_file(dir / "run.json"));
  CHECK(run["steps"] == 20);
  CHECK(run["steps_requested"] == 1000);
  // The probe moved rigidly by the target's offset from its start.
  CHECK((centre_end - centre_start - Vec3(0.01, 0.02, -0.03)).norm() < 1e-12);

  const auto frame = session->next_frame(0, 0.0);
  CHECK_FALSE(frame);  // stopped: no more frames
  session->save_path(dir / "probe_path.csv");
  const Trajectory path = read_trajectory_csv(dir / "probe_path.csv");
  REQUIRE(path.time_s.size() == 21);  // the start and one target per step
  CHECK(path.position_m.front() == start);
  CHECK(path.position_m.back() == start + Vec3(0.01, 0.02, -0.03));
  CHECK(path.time_s.back() == Approx(20 * scene.world.dt_s));
  fs::remove_all(dir);
}

TEST_CASE("live: frames carry the surface, contacts, the probe's force and the loop's pace", "[live]") {
  const SceneDesc scene = load_scene_file(resolve_scene("haptic_probe", default_scene_dirs()));
  const fs::path dir = fs::temp_directory_path() / ("tcbench_live_frames_" + std::to_string(::getpid()));
  RunOptions options;
  options.out_dir = dir;
  options.steps = 5;
  std::unique_ptr<LiveSession> session;
  options.before_step = [&](World& world) {
    if (!session) session = std::make_unique<LiveSession>(world, 1, scene.world.dt_s, 0.5);
    session->drive(world);
  };
  std::optional<std::pair<std::uint64_t, std::string>> first;
  options.after_step = [&](const StepContext& ctx) {
    const bool more = session->after_step(ctx);
    if (!first) first = session->next_frame(0, 0.0);  // the first step always publishes
    return more;
  };
  REQUIRE(run_scene(scene, options).status == "ok");
  REQUIRE(first);
  CHECK(first->first == 1);
  const auto f = nlohmann::json::parse(first->second);
  const auto s = nlohmann::json::parse(session->scene_json());
  CHECK(s["schema"] == "tcbench.live/1");
  CHECK(s["probe"] == 1);
  CHECK(f["positions"].size() == 3 * s["surface_body"].size());
  CHECK(f["step"] == 1);
  CHECK(f["budget_ms"] == 0.5);
  CHECK(f["target_rate_hz"] == Approx(1000.0));
  CHECK(f["probe_force_n"].size() == 3);
  CHECK(f["contacts"].is_array());
  for (std::size_t i = 0; i < s["triangles"].size(); ++i) CHECK(s["triangles"][i] < s["surface_body"].size());
  fs::remove_all(dir);
}
