// tcbench live SCENE: the simulation in its own thread, streamed to the
// viewer page; the mouse drives the scene's probe (seed 001's interaction).
#include <fmt/format.h>

#include <condition_variable>
#include <exception>
#include <iostream>
#include <mutex>
#include <thread>

#include "baselines/registry.hpp"
#include "experiments/cli/command.hpp"
#include "experiments/cli/option_checks.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "experiments/view/live_session.hpp"
#include "experiments/view/local_server.hpp"
#include "sim/io/input_error.hpp"

// Last: through <resolv.h> it defines the macro _res, a parameter name in Eigen.
#include <httplib.h>

namespace tcb::cli {
namespace {

// The session appears once the simulation thread has built the world; the
// server's handlers wait for it (or for the run's end) here.
struct SessionSlot {
  std::mutex mutex;
  std::condition_variable ready;
  std::unique_ptr<LiveSession> session;
  bool ended = false;
  std::exception_ptr error;  ///< what ended the run early (bad input: exit 2)
  RunOutcome outcome;

  LiveSession* wait(double timeout_s) {
    std::unique_lock lock(mutex);
    ready.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return session || ended; });
    return session.get();
  }
};

class LiveCommand final : public Command {
 public:
  explicit LiveCommand(CLI::App& parent) {
    app = parent.add_subcommand(
        "live",
        "Run a scene live in the browser: the simulation runs in real time in its own thread, the page at the "
        "printed address\nshows it, and the mouse drives the scene's probe (drag: x and y; wheel: z). "
        "The probe's contact force,\nthe loop's rate and its budget overshoot are drawn live. Ctrl-C stops; the "
        "run's files and the probe's path\n(probe_path.csv, replayable with `tcbench run SCENE --set "
        "object.PROBE.trajectory=FILE`) are written to --out.\nExit status: 0 stopped cleanly; 1 the run went "
        "unstable (files kept); 2 bad input.");
    app->add_option("SCENE", m_scene, "A scene with a driven probe (a passive object with a trajectory), e.g. haptic_probe")
        ->required();
    app->add_option("--method", m_options.method, "Collision handling method (tcbench list methods)")->capture_default_str();
    app->add_option("--budget-ms", m_budget_ms, "Wall-clock budget per step, ms");
    app->add_option("--probe", m_probe, "The driven object the mouse moves (default: the first one)");
    app->add_option("--set", m_options.overrides, "Override a scene key, e.g. --set object.cow.material.youngs_modulus=2e5");
    app->add_option("--seconds", m_seconds, "Stop after this much simulated time (default 600 s)")
        ->transform(whole_number(1, 86400));
    app->add_option("--out", m_out, "Result directory (default: results/live/SCENE-METHOD)")->check(non_empty_path());
    app->add_option("--port", m_port, "Port on 127.0.0.1; 0 picks a free one")->capture_default_str();
    app->add_option("--viewer", m_viewer, "The viewer page's directory (default: viewer/ in the source tree)");
  }

  int execute() override {
    const SceneDesc scene = load_scene_file(resolve_scene(m_scene, default_scene_dirs()), m_options.overrides);
    std::string probe;
    for (const ObjectDesc& o : scene.world.objects)
      if (!o.trajectory.empty() && (m_probe.empty() || o.name == m_probe)) {
        probe = o.name;
        break;
      }
    if (probe.empty())
      throw InputError(m_probe.empty() ? scene.path.string() : "--probe", 0,
                       m_probe.empty() ? "has no driven probe for the mouse (a passive object with a trajectory)"
                                       : "'" + m_probe + "' is not a driven object of " + scene.name);
    double budget_ms = 0.0;
    if (!m_budget_ms.empty()) {
      const auto spec = BudgetSpec::parse("ms:" + m_budget_ms);
      if (!spec) throw InputError("--budget-ms", 0, "'" + m_budget_ms + "' is not a plain decimal number of milliseconds >= 0");
      m_options.budget = *spec;
      budget_ms = spec->value;
    }
    find_method(m_options.method);  // an unknown method is exit 2 now, not after the address is printed
    const std::filesystem::path viewer = viewer_directory(m_viewer);
    m_options.out_dir = m_out.empty() ? std::filesystem::path("results/live") / (scene.name + "-" + m_options.method)
                                      : std::filesystem::path(m_out);
    m_options.steps = static_cast<std::int64_t>(m_seconds / scene.world.dt_s);
    m_options.argv = argv;
    m_options.timing_floor = false;  // paced to real time: no spare budget to spin
    m_options.on_warning = [](const std::string& w) { std::cerr << "tcbench: warning: " << w << '\n'; };

    SessionSlot slot;
    m_options.before_step = [&](World& world) {
      if (!slot.session) {
        std::size_t body = 0;
        while (world.bodies[body].name != probe) ++body;  // build_world keeps the object's name
        std::lock_guard lock(slot.mutex);
        slot.session = std::make_unique<LiveSession>(world, body, scene.world.dt_s, budget_ms);
        slot.ready.notify_all();
      }
      slot.session->drive(world);
    };
    m_options.after_step = [&](const StepContext& ctx) { return slot.session->after_step(ctx); };

    std::thread simulation;
    const auto finished = [&] {
      std::lock_guard lock(slot.mutex);
      return slot.ended;
    };
    const auto run = [&] {
      RunOutcome outcome;
      std::exception_ptr error;
      try {
        outcome = run_scene(scene, m_options);
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard lock(slot.mutex);
      slot.outcome = outcome;
      slot.error = error;
      slot.ended = true;
      slot.ready.notify_all();
    };
    const int served = serve_locally(
          viewer, m_port, "live",
          [&](httplib::Server& server) {
            server.Get("/mode.json", [](const httplib::Request&, httplib::Response& response) {
              response.set_content(R"({"mode":"live"})", "application/json");
            });
            server.Get("/live/scene.json", [&](const httplib::Request&, httplib::Response& response) {
              LiveSession* session = slot.wait(30.0);
              if (!session) {
                response.status = 503;
                response.set_content("tcbench live: the simulation is not running\n", "text/plain");
                return;
              }
              response.set_content(session->scene_json(), "application/json");
            });
            // Server-sent events: the newest frame, about 30 a second.
            server.Get("/live/events", [&](const httplib::Request&, httplib::Response& response) {
              LiveSession* session = slot.wait(30.0);
              if (!session) {
                response.status = 503;
                return;
              }
              response.set_header("Cache-Control", "no-store");
              response.set_chunked_content_provider(
                  "text/event-stream", [session, seen = std::uint64_t{0}](std::size_t, httplib::DataSink& sink) mutable {
                    const auto frame = session->next_frame(seen, 1.0);
                    if (session->stopped()) {
                      sink.done();
                      return false;
                    }
                    if (!frame) return sink.write(": idle\n\n", 8);
                    seen = frame->first;
                    const std::string event = "data: " + frame->second + "\n\n";
                    return sink.write(event.data(), event.size());
                  });
            });
            server.Post("/live/probe", [&](const httplib::Request& request, httplib::Response& response) {
              // JSON only: a page of another origin cannot send that without a
              // preflight, which this server never grants, so it cannot move the probe.
              if (request.get_header_value("Content-Type").rfind("application/json", 0) != 0) {
                response.status = 415;
                response.set_content("tcbench live: send the target as Content-Type: application/json\n", "text/plain");
                return;
              }
              const ProbeMessage message = parse_probe_message(request.body);
              if (!message.position_m) {
                response.status = 400;
                response.set_content("tcbench live: " + message.error + "\n", "text/plain");
                return;
              }
              LiveSession* session = slot.wait(30.0);
              if (!session) {
                response.status = 503;
                response.set_content("tcbench live: the simulation is not running\n", "text/plain");
                return;
              }
              if (!session->set_target(*message.position_m)) {
                response.status = 400;
                response.set_content(fmt::format("tcbench live: the probe may move at most {:.3g} m from its start\n",
                                                 session->reach_m()),
                                     "text/plain");
                return;
              }
              response.set_content("{}", "application/json");
            });
          },
          {.on_listening = [&] { simulation = std::thread(run); },
           .on_stop =
               [&] {
                 std::lock_guard lock(slot.mutex);
                 if (slot.session) slot.session->stop();
               },
           .finished = finished});
    {
      // The server stopped (Ctrl-C or the run ended): end the run; its files are written.
      std::unique_lock lock(slot.mutex);
      slot.ready.wait(lock, [&] { return slot.session || slot.ended; });
      if (slot.session) slot.session->stop();
    }
    if (simulation.joinable()) simulation.join();
    if (slot.error) std::rethrow_exception(slot.error);
    if (slot.session) slot.session->save_path(m_options.out_dir / "probe_path.csv");
    if (slot.outcome.status != "ok") {
      std::cerr << fmt::format("tcbench: run unstable: {}; {} steps written to {}\n", slot.outcome.reason,
                               slot.outcome.steps_done, m_options.out_dir.string());
      return 1;
    }
    std::cout << fmt::format("{} [{}] live: {} steps ({:.2f} s simulated) -> {} (probe path: probe_path.csv)\n",
                             scene.name, m_options.method, slot.outcome.steps_done,
                             static_cast<double>(slot.outcome.steps_done) * scene.world.dt_s, m_options.out_dir.string());
    return served;
  }

 private:
  std::string m_scene, m_out, m_budget_ms, m_probe;
  std::int64_t m_seconds = 600;
  int m_port = 8766;
  std::filesystem::path m_viewer;
  RunOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_live_command(CLI::App& parent) { return std::make_unique<LiveCommand>(parent); }

}  // namespace tcb::cli
