// Which runs are repeats of one configuration: the mesh order splits them
// (a renumbered mesh is the same scene, not the same bits), and a run
// recorded before the field counts as the file's order.
#include "experiments/results/run_collection.hpp"

#include <catch2/catch.hpp>

using namespace tcb;

TEST_CASE("runs in the file's order and renumbered along the curve are different configurations", "[results]") {
  const nlohmann::json older = nlohmann::json::parse(R"({"scene": "plates20", "method": "full", "seed": 1,
      "budget": {"kind": "none", "label": "none"}, "response": "implicit", "steps_requested": 10,
      "overrides": []})");
  nlohmann::json file = older, curve = older, other_seed = older;
  file["world"] = {{"mesh_order", "file"}};
  curve["world"] = {{"mesh_order", "curve"}};
  other_seed["seed"] = 2;
  CHECK(mesh_order_of(older) == "file");
  CHECK(mesh_order_of(curve) == "curve");
  CHECK(configuration_key(file) == configuration_key(older));
  CHECK(configuration_key(other_seed) == configuration_key(older));  // repeats: only the seed differs
  CHECK(configuration_key(curve) != configuration_key(file));
  CHECK(configuration_label(file) == "plates20 full none implicit 10 steps");
  CHECK(configuration_label(curve) == "plates20 full none implicit 10 steps mesh_order=curve");
}
