// tcbench view RUN_DIR [RUN_DIR]: plays recorded runs in the browser.
#include <httplib.h>

#include <nlohmann/json.hpp>

#include "experiments/cli/command.hpp"
#include "experiments/view/local_server.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"

namespace tcb::cli {
namespace {

// What the page may read from a run directory; nothing else in it is served.
constexpr const char* kRunFiles[] = {"replay.json", "replay.bin", "steps.csv", "run.json"};

class ViewCommand final : public Command {
 public:
  explicit ViewCommand(CLI::App& parent) {
    app = parent.add_subcommand(
        "view",
        "Play recorded runs in the browser: serves the viewer page on 127.0.0.1 and prints its address.\n"
        "Record a run with `tcbench run SCENE --record N [--record-debug]`; two runs play side by side in "
        "lockstep.\nKeys: Space play/pause, arrows step, W wireframe, B boxes, G hash grid, Backspace debug "
        "overlays, V four views.\nExit status: 0 stopped with Ctrl-C; 2 bad input (no replay in a directory, "
        "port in use).");
    app->add_option("RUN_DIR", m_runs, "One or two run directories holding replay.json (made with --record)")
        ->required()
        ->expected(1, 2);
    app->add_option("--port", m_port, "Port on 127.0.0.1; 0 picks a free one")->capture_default_str();
    app->add_option("--viewer", m_viewer, "The viewer page's directory (default: viewer/ in the source tree)");
  }

  int execute() override {
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& dir : m_runs) {
      if (!std::filesystem::is_directory(dir)) throw InputError(dir.string(), 0, "not a run directory");
      if (!std::filesystem::is_regular_file(dir / "replay.json"))
        throw InputError(dir.string(), 0, "holds no replay.json (record one with `tcbench run ... --record N`)");
      nlohmann::json files = nlohmann::json::array();
      for (const char* f : kRunFiles)
        if (std::filesystem::is_regular_file(dir / f)) files.push_back(f);
      const auto name = std::filesystem::absolute(dir).lexically_normal();
      runs.push_back({{"name", (name.has_filename() ? name : name.parent_path()).filename().string()},
                      {"path", name.string()},
                      {"files", files}});
    }
    const std::filesystem::path viewer = viewer_directory(m_viewer);
    return serve_locally(viewer, m_port, "view", [&](httplib::Server& server) {
      server.Get("/mode.json", [](const httplib::Request&, httplib::Response& response) {
        response.set_content(R"({"mode":"view"})", "application/json");
      });
      server.Get("/runs.json", [runs](const httplib::Request&, httplib::Response& response) {
        response.set_content(runs.dump(), "application/json");
      });
      server.Get(R"(/run/(\d+)/([a-z_.]+))", [this](const httplib::Request& request, httplib::Response& response) {
        const std::size_t index = std::stoul(request.matches[1]);
        const std::string file = request.matches[2];
        bool allowed = false;
        for (const char* f : kRunFiles) allowed = allowed || file == f;
        if (index >= m_runs.size() || !allowed || !std::filesystem::is_regular_file(m_runs[index] / file)) {
          response.status = 404;
          return;
        }
        response.set_content(read_file(m_runs[index] / file), content_type_for(file));
      });
    });
  }

 private:
  std::vector<std::filesystem::path> m_runs;
  int m_port = 8765;
  std::filesystem::path m_viewer;
};

}  // namespace

std::unique_ptr<Command> make_view_command(CLI::App& parent) { return std::make_unique<ViewCommand>(parent); }

}  // namespace tcb::cli
