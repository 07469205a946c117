// The living documents stay true: every steps.csv column, summary key and
// run.json field a real run writes is in docs/contract.md, every method and
// setting too; every source folder is in docs/architecture.md; and the
// include arrows go the one way docs/architecture.md says.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <fstream>
#include <regex>

#include "baselines/registry.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_scene.hpp"
#include "experiments/scene/scene_file.hpp"
#include "sim/io/atomic_file.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

std::string documented(const std::string& name) { return "`" + name + "`"; }

}  // namespace

TEST_CASE("docs/contract.md lists every column, summary key and run.json field of a real run", "[docs]") {
  const std::string contract = read_file(source_tree_dir() / "docs" / "contract.md");
  // The oracle on every step and the overlap volume: every meter has something to say.
  const SceneDesc scene = load_scene_file(resolve_scene("fast_sphere_torus", default_scene_dirs()));
  RunOptions options;
  options.method = "interruptible";
  options.budget = {BudgetKind::WallMs, 1.0};
  options.oracle = {1};
  options.steps = 3;
  options.out_dir = fs::temp_directory_path() / ("tcbench_docs_" + std::to_string(::getpid()));
  REQUIRE(run_scene(scene, options).status == "ok");
  std::ifstream csv(options.out_dir / "steps.csv");
  std::string header;
  std::getline(csv, header);
  std::stringstream columns(header);
  int checked = 0;
  for (std::string column; std::getline(columns, column, ',');) {
    INFO("steps.csv column " << column);
    CHECK_THAT(contract, Catch::Matchers::Contains(documented(column)));
    ++checked;
  }
  const auto run = nlohmann::json::parse(read_file(options.out_dir / "run.json"));
  for (const auto& [key, value] : run.items()) {
    INFO("run.json field " << key);
    CHECK_THAT(contract, Catch::Matchers::Contains(documented(key)));
    ++checked;
  }
  for (const auto& [key, value] : run["summary"].items()) {
    INFO("summary key " << key);
    CHECK_THAT(contract, Catch::Matchers::Contains(documented(key)));
    ++checked;
  }
  CHECK(checked > 60);  // the run really wrote them
  fs::remove_all(options.out_dir);
}

TEST_CASE("docs/contract.md lists every method and its settings", "[docs]") {
  const std::string contract = read_file(source_tree_dir() / "docs" / "contract.md");
  for (const MethodInfo& m : method_registry()) {
    INFO(m.name);
    CHECK_THAT(contract, Catch::Matchers::Contains(documented(m.name)));
    for (const SettingSpec& s : m.settings) CHECK_THAT(contract, Catch::Matchers::Contains(documented(s.name)));
  }
}

TEST_CASE("docs/architecture.md names every source folder", "[docs]") {
  const std::string architecture = read_file(source_tree_dir() / "docs" / "architecture.md");
  int folders = 0;
  for (const char* top : {"sim", "method", "baselines", "oracle", "experiments", "report"}) {
    CHECK_THAT(architecture, Catch::Matchers::Contains(documented(std::string(top) + "/")));
    for (const auto& entry : fs::directory_iterator(source_tree_dir() / top)) {
      if (!entry.is_directory() || entry.path().filename().string().front() == '_') continue;
      INFO(entry.path());
      CHECK_THAT(architecture, Catch::Matchers::Contains(documented(entry.path().filename().string() + "/")));
      ++folders;
    }
  }
  CHECK(folders > 15);
}

TEST_CASE("includes go the one way below experiments: sim <- method <- baselines, oracle never sees method",
          "[docs]") {
  // What each library may include of the project (docs/architecture.md "Layers").
  const std::vector<std::pair<std::string, std::vector<std::string>>> allowed = {
      {"sim", {"sim/"}},
      {"method", {"method/", "sim/"}},
      {"baselines", {"baselines/", "method/", "sim/"}},
      {"oracle", {"oracle/", "sim/"}},
  };
  const std::regex include(R"re(#include\s+"([^"]+)")re");
  int files = 0;
  for (const auto& [folder, prefixes] : allowed) {
    for (const auto& entry : fs::recursive_directory_iterator(source_tree_dir() / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".hpp" && ext != ".cpp") continue;
      ++files;
      const std::string text = read_file(entry.path());
      for (auto it = std::sregex_iterator(text.begin(), text.end(), include); it != std::sregex_iterator(); ++it) {
        const std::string target = (*it)[1];
        if (target.find('/') == std::string::npos) continue;  // generated or local headers
        const bool ok = std::any_of(prefixes.begin(), prefixes.end(),
                                    [&](const std::string& p) { return target.rfind(p, 0) == 0; });
        INFO(entry.path().string() << " includes " << target);
        CHECK(ok);
      }
      // The oracle is the only CGAL user; FCL (and libccd) appear besides only
      // in the baseline built on them, never in sim/ or method/.
      if (folder != "oracle") CHECK(text.find("#include <CGAL/") == std::string::npos);
      if (folder != "oracle" && entry.path().filename() != "fcl_tets_handler.cpp") {
        CHECK(text.find("#include <fcl/") == std::string::npos);
        CHECK(text.find("#include <ccd/") == std::string::npos);
      }
    }
  }
  CHECK(files > 40);
}
