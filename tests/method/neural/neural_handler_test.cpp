// The `neural` method: one network evaluation per latent-driven body and
// step, the verdict the sign of the logit, the budget obeyed, and clear
// errors for scenes it cannot judge.
#include "method/neural/neural_handler.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/io/input_error.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;
namespace fs = std::filesystem;

namespace {

struct Fixture {
  fs::path dir = fs::temp_directory_path() / ("tcbench_neural_handler_" + std::to_string(::getpid()));
  WorldDesc desc;
  neural::Mlp<double> net{{12, 8, 1}, neural::Activation::Tanh, 7};
  Fixture() {
    fs::create_directories(dir);
    // Straight, then a curl of every joint by steps of 0.25 in z, 1 ms apart.
    std::ofstream csv(dir / "path.csv");
    csv << "time_s";
    for (int k = 0; k < 12; ++k) csv << ",z" << k;
    csv << "\n";
    for (int i = 0; i <= 8; ++i) {
      csv << i * 1e-3;
      for (int k = 0; k < 12; ++k) csv << "," << (k % 2 == 0 ? -1.0 + 0.25 * i : 0.1 * (i % 3));
      csv << "\n";
    }
    net.save((dir / "net.json").string());
    ObjectDesc o;
    o.name = "finger";
    o.mesh = "finger:finger_small";
    o.passive = true;
    o.self_collision = true;
    o.latent_path = "path.csv";
    o.latent_model = "net.json";
    o.base_dir = dir;
    desc.objects.push_back(o);
  }
  ~Fixture() { fs::remove_all(dir); }
};

}  // namespace

TEST_CASE("neural handler: the verdict is the network's logit sign at the body's current code", "[neural]") {
  Fixture f;
  World world = build_world(f.desc);
  NeuralHandler handler;
  handler.init(world, CollisionSettings{});
  CHECK_FALSE(handler.reports_points());
  int positives = 0, negatives = 0;
  for (int step = 0; step < 8; ++step) {
    Budget unlimited = Budget::unlimited();
    const StepReport report = handler.step(world, unlimited);
    const double logit = f.net.forward(world.bodies[0].latent_code)[0];
    CHECK(handler.logits()[0] == logit);
    const bool says = handler.self_collision_verdicts(world)[0];
    CHECK(says == (logit > 0.0));
    CHECK(report.work_units == 1);
    CHECK(report.colliding_points == (says ? 1 : 0));
    CHECK(handler.contacts().empty());
    (says ? positives : negatives)++;
    world.step(1e-3);
  }
  INFO("positives " << positives << ", negatives " << negatives);
  // The path crosses the untrained network's level set, so both verdicts occur
  // and the check above is not vacuous (seed 7 of the initialisation).
  CHECK(positives > 0);
  CHECK(negatives > 0);
}

TEST_CASE("neural handler: a spent budget skips the evaluation and keeps the last verdict", "[neural]") {
  Fixture f;
  World world = build_world(f.desc);
  NeuralHandler handler;
  handler.init(world, CollisionSettings{});
  Budget none_left = Budget::work_units(0);
  StepReport report = handler.step(world, none_left);
  CHECK(report.work_units == 0);
  CHECK(std::isnan(handler.logits()[0]));  // never evaluated
  CHECK(handler.self_collision_verdicts(world)[0] == 0);
  Budget one = Budget::work_units(1);
  report = handler.step(world, one);
  CHECK(report.work_units == 1);
  const double first = handler.logits()[0];
  CHECK(first == f.net.forward(world.bodies[0].latent_code)[0]);
  for (int i = 0; i < 4; ++i) world.step(1e-3);
  Budget spent = Budget::work_units(0);
  handler.step(world, spent);
  CHECK(handler.logits()[0] == first);  // stale, as documented
}

TEST_CASE("neural handler: scenes it cannot judge are bad input", "[neural]") {
  Fixture f;
  SECTION("no latent-driven object") {
    WorldDesc desc;
    ObjectDesc box;
    box.name = "box";
    box.mesh = "box:size=1x1x1,cells=2x2x2";
    desc.objects.push_back(box);
    World world = build_world(desc);
    NeuralHandler handler;
    CHECK_THROWS_AS(handler.init(world, CollisionSettings{}), InputError);
  }
  SECTION("no model named") {
    f.desc.objects[0].latent_model.clear();
    World world = build_world(f.desc);
    NeuralHandler handler;
    CHECK_THROWS_WITH(handler.init(world, CollisionSettings{}), Catch::Matchers::Contains("names no latent_model"));
  }
  SECTION("a network of the wrong input size") {
    neural::Mlp<double>({5, 4, 1}, neural::Activation::Tanh, 1).save((f.dir / "net.json").string());
    World world = build_world(f.desc);
    NeuralHandler handler;
    CHECK_THROWS_WITH(handler.init(world, CollisionSettings{}), Catch::Matchers::Contains("takes 5 inputs"));
  }
  SECTION("a network trained for the other finger (both have 12 latent entries)") {
    auto j = f.net.to_json();
    j["trained"] = {{"preset", "finger_large"}};
    std::ofstream(f.dir / "net.json") << j.dump();
    World world = build_world(f.desc);
    NeuralHandler handler;
    CHECK_THROWS_WITH(handler.init(world, CollisionSettings{}),
                      Catch::Matchers::Contains("trained for finger_large, but object 'finger' is a finger_small"));
  }
  SECTION("a file that is no network") {
    std::ofstream(f.dir / "net.json") << "{\"format\": \"something else\"}";
    World world = build_world(f.desc);
    NeuralHandler handler;
    CHECK_THROWS_WITH(handler.init(world, CollisionSettings{}), Catch::Matchers::Contains("net.json"));
  }
  SECTION("a header that claims huge layers is refused before anything is allocated") {
    std::ofstream(f.dir / "net.json")
        << R"({"format": "tcbench-mlp-1", "activation": "tanh", "layers": [12, 100000, 100000, 1], "parameters": [0]})";
    World world = build_world(f.desc);
    NeuralHandler handler;
    CHECK_THROWS_WITH(handler.init(world, CollisionSettings{}), Catch::Matchers::Contains("must be an array of 10001500001"));
  }
}
