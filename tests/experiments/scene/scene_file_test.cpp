#include "experiments/scene/scene_file.hpp"

#include <catch2/catch.hpp>

#include "sim/io/input_error.hpp"

using namespace tcb;
using Catch::Matchers::Contains;

namespace {

const char* kScene = R"(# a test scene
[scene]
dt = 0.002
steps = 10
gravity = [0.0, -1.0, 0.0]

[ground]
height = -0.5
friction = 0.25

[collision]
cell_size = 0.05
response_stiffness = 2.0e4

[[object]]
name = "plate"
mesh = "box:size=1x0.1x1,cells=2x1x2"
position = [0.0, 1.0, 0.0]
stack = { count = 3, axis = "y", gap = 0.01 }
material = { model = "mass_spring", integrator = "verlet", youngs_modulus = 2.0e5, density = 500 }

[[object]]
name = "floor"
mesh = "box:size=3x0.1x3"
passive = true
)";

struct BadCase {
  const char* name;
  std::string text;
  std::vector<std::string> overrides;
  std::string file;
  int line;
  const char* message;
};

// The case's text, read as `path`, is rejected with its file, line and message.
void check_rejected(const BadCase& c, const std::string& path) {
  INFO(c.name);
  try {
    parse_scene(c.text, path, c.overrides);
    FAIL("accepted: " << c.name);
  } catch (const InputError& e) {
    CHECK(e.file() == c.file);
    CHECK(e.line() == c.line);
    CHECK_THAT(e.what(), Contains(c.message));
  }
}

}  // namespace

TEST_CASE("scene file: every key read", "[scene]") {
  const SceneDesc s = parse_scene(kScene, "dir/test.toml");
  CHECK(s.name == "test");
  CHECK(s.world.dt_s == 0.002);
  CHECK(s.steps == 10);
  CHECK(s.world.gravity_m_per_s2 == Vec3(0, -1, 0));
  CHECK(s.world.mesh_order == MeshOrder::File);  // the default: the paper's runs
  CHECK(parse_scene(kScene, "dir/test.toml", {"scene.mesh_order=curve"}).world.mesh_order == MeshOrder::Curve);
  REQUIRE(s.world.ground);
  CHECK(s.world.ground->height_m == -0.5);
  CHECK(s.world.ground->friction == 0.25);
  CHECK(s.collision.cell_size_m == 0.05);
  CHECK(s.collision.response_stiffness_n_per_m == 2.0e4);
  REQUIRE(s.world.objects.size() == 2);
  const ObjectDesc& plate = s.world.objects[0];
  CHECK(plate.base_dir == "dir");
  CHECK(plate.source_line == 15);
  CHECK(plate.stack.count == 3);
  CHECK(plate.stack.gap_m == 0.01);
  CHECK(plate.material.model == MaterialModel::MassSpring);
  CHECK(plate.material.integrator == Integrator::VelocityVerlet);
  CHECK(plate.material.youngs_modulus_pa == 2.0e5);
  CHECK(plate.material.density_kg_per_m3 == 500.0);
  CHECK(s.world.objects[1].passive);
}

TEST_CASE("scene file: --set overrides, by name and by index, and new tables", "[scene]") {
  const SceneDesc s = parse_scene(kScene, "t.toml",
                                  {"scene.dt=0.004", "object.plate.material.youngs_modulus=3e5", "object.1.scale=2",
                                   "object.plate.material.model=corotational_fem",
                                   "object.plate.material.integrator=implicit_euler", "collision.cell_size=auto",
                                   "object.floor.velocity=[1, 2, 3]"});
  CHECK(s.world.dt_s == 0.004);
  CHECK(s.world.objects[0].material.youngs_modulus_pa == 3e5);
  CHECK(s.world.objects[0].material.model == MaterialModel::CorotationalFem);
  CHECK(s.world.objects[1].scale == 2.0);
  CHECK(s.world.objects[1].velocity_m_per_s == Vec3(1, 2, 3));
  CHECK_FALSE(s.collision.cell_size_m.has_value());
  const std::string no_ground = "[[object]]\nmesh = \"box:size=1x1x1\"\n";
  CHECK_FALSE(parse_scene(no_ground, "g.toml").world.ground);
  const SceneDesc with_ground = parse_scene(no_ground, "g.toml", {"ground.height=0.5"});
  REQUIRE(with_ground.world.ground);
  CHECK(with_ground.world.ground->height_m == 0.5);
}

TEST_CASE("scene file: malformed input names the file, the line and the problem", "[scene]") {
  const std::string obj = "[[object]]\nmesh = \"box:size=1x1x1\"\n";
  const BadCase cases[] = {
      {"TOML syntax", "[scene]\ndt = = 1\n", {}, "bad.toml", 2, ""},
      {"unknown key", "[scene]\ndtt = 0.1\n" + obj, {}, "bad.toml", 2, "unknown key 'dtt' in scene"},
      {"unknown table", "[sceen]\ndt = 0.1\n" + obj, {}, "bad.toml", 1, "unknown key 'sceen'"},
      {"wrong type", "[scene]\ndt = \"fast\"\n" + obj, {}, "bad.toml", 2, "scene.dt: must be a number"},
      {"negative dt", "[scene]\ndt = -0.1\n" + obj, {}, "bad.toml", 2, "must be positive"},
      {"NaN dt", "[scene]\ndt = nan\n" + obj, {}, "bad.toml", 2, "must be finite"},
      {"fractional steps", "[scene]\nsteps = 1.5\n" + obj, {}, "bad.toml", 2, "whole number"},
      {"short gravity", "[scene]\ngravity = [0, 1]\n" + obj, {}, "bad.toml", 2, "three numbers"},
      {"mesh order", "[scene]\nmesh_order = \"zorder\"\n" + obj, {}, "bad.toml", 2,
       "scene.mesh_order: is 'zorder'; must be \"file\""},
      {"no objects", "[scene]\ndt = 0.1\n", {}, "bad.toml", 0, "no [[object]]"},
      {"object without mesh", "[[object]]\nname = \"a\"\n", {}, "bad.toml", 1, "object 'a' has no mesh"},
      {"duplicate names", obj + "name = \"a\"\n" + obj + "name = \"a\"\n", {}, "bad.toml", 4, "two objects are named 'a'"},
      {"unknown object key", obj + "colour = \"red\"\n", {}, "bad.toml", 3, "unknown key 'colour'"},
      {"bad material model", obj + "material = { model = \"jelly\" }\n", {}, "bad.toml", 3, "\"jelly\""},
      {"poisson 0.5", obj + "material = { poisson_ratio = 0.5 }\n", {}, "bad.toml", 3, "strictly between"},
      {"fem with verlet", obj + "material = { integrator = \"verlet\" }\n", {}, "bad.toml", 3, "\"implicit_euler\" only"},
      {"stack axis", obj + "stack = { count = 2, axis = \"w\" }\n", {}, "bad.toml", 3, "\"x\", \"y\" or \"z\""},
      {"zero stack", obj + "stack = { count = 0 }\n", {}, "bad.toml", 3, "must lie in [1, 100000]"},
      {"a stack copy's name taken", obj + "name = \"a\"\nstack = { count = 2 }\n" + obj + "name = \"a_01\"\n", {},
       "bad.toml", 5, "the name 'a_01' is both a body of the stack 'a' and object 'a_01'"},
      {"an object's name taken by a later stack", obj + "name = \"a_00\"\n" + obj + "name = \"a\"\nstack = { count = 3 }\n",
       {}, "bad.toml", 4, "the name 'a_00' is both object 'a_00' and a body of the stack 'a'"},
      {"a stack named like an object", obj + "name = \"a\"\n" + obj + "name = \"a\"\nstack = { count = 2 }\n", {},
       "bad.toml", 4, "two objects are named 'a'"},
      {"a stack named like another stack's body",
       obj + "name = \"b\"\nstack = { count = 2 }\n" + obj + "name = \"b_00\"\nstack = { count = 2 }\n", {}, "bad.toml", 5,
       "the name 'b_00' is both a body of the stack 'b' and object 'b_00'"},
      {"a stacked driven object", obj + "passive = true\ntrajectory = \"t.csv\"\nstack = { count = 2 }\n", {},
       "bad.toml", 5, "a driven object (trajectory or latent_path) cannot be stacked"},
      {"scene name with a slash", "[scene]\nname = \"../x\"\n" + obj, {}, "bad.toml", 2,
       "must be a non-empty name without '/'"},
      {"scene name empty", "[scene]\nname = \"\"\n" + obj, {}, "bad.toml", 2, "must be a non-empty name"},
      {"object not array", "object = 3\n", {}, "bad.toml", 1, "[[object]]"},
      {"cell size", "[collision]\ncell_size = -1\n" + obj, {}, "bad.toml", 2, "\"auto*K\" or a positive length"},
      {"cell size subnormal", "[collision]\ncell_size = 1e-310\n" + obj, {}, "bad.toml", 2, "its inverse overflows"},
      {"cell size inf", "[collision]\ncell_size = inf\n" + obj, {}, "bad.toml", 2, "collision.cell_size: must be finite"},
      {"cell size auto*word", "[collision]\ncell_size = \"auto*big\"\n" + obj, {}, "bad.toml", 2, "\"auto*K\" (K > 0"},
      {"cell size auto*0", "[collision]\ncell_size = \"auto*0\"\n" + obj, {}, "bad.toml", 2, "\"auto*K\" (K > 0"},
      {"table size auto*-1", "[collision]\ntable_size = \"auto*-1\"\n" + obj, {}, "bad.toml", 2, "next prime above 2 K tets"},
      {"perturb material 1", "[perturb]\nmaterial = 1.0\n" + obj, {}, "bad.toml", 2, "must be below 1"},
      {"perturb negative", "[perturb]\nvelocity = -1\n" + obj, {}, "bad.toml", 2, "perturb.velocity"},
      {"perturb unknown key", "[perturb]\nspin = 1\n" + obj, {}, "bad.toml", 2, "unknown key 'spin' in perturb"},
      {"perturb a passive object", obj + "passive = true\nperturb = { position = 1e-3 }\n", {}, "bad.toml", 4,
       "passive objects are not perturbed"},
      {"--set bad value", obj, {"scene.dt=abc"}, "--set scene.dt=abc", 0, "must be a number"},
      {"--set unknown key", obj, {"scene.dtt=1"}, "--set scene.dtt=1", 0, "unknown key 'dtt'"},
      {"--set no such object", obj, {"object.b.scale=2"}, "--set object.b.scale=2", 0, "no object named"},
      {"--set no equals", obj, {"scene.dt"}, "--set scene.dt", 0, "expected key=value"},
      {"--set contradicts the file", kScene, {"object.plate.material.model=corotational_fem"}, "bad.toml", 20,
       "integrates with \"implicit_euler\" only"},
      {"--set into a value", obj, {"object.0.mesh.x=1"}, "--set object.0.mesh.x=1", 0, "not a table"},
      // Tables an override makes, and the keys of an inline table it gives,
      // are the override's, not the file's.
      {"--set a new top-level table", obj, {"nosuch.key=1"}, "--set nosuch.key=1", 0, "unknown key 'nosuch'"},
      {"--set a new method table", obj, {"method.nosuch.x=1"}, "--set method.nosuch.x=1", 0, "no method of that name"},
      {"--set an inline table's key", obj, {"object.0.material={bogus=1}"}, "--set object.0.material={bogus=1}", 0,
       "unknown key 'bogus'"},
      {"--set an inline table's value", obj, {"ground={height=\"x\"}"}, "--set ground={height=\"x\"}", 0,
       "ground.height: must be a number"},
      {"--set a nested inline value", obj, {"object.0.stack={count=2,gap=inf}"}, "--set object.0.stack={count=2,gap=inf}",
       0, "stack.gap: must be finite"},
      {"latent path, not passive", "[[object]]\nmesh = \"finger:finger_small\"\nlatent_path = \"p.csv\"\n", {},
       "bad.toml", 3, "a latent-driven object must be passive = true"},
      {"latent path on a box", obj + "passive = true\nlatent_path = \"p.csv\"\n", {}, "bad.toml", 4,
       "needs a latent family as the mesh"},
      {"latent path and trajectory",
       "[[object]]\nmesh = \"finger:finger_small\"\npassive = true\ntrajectory = \"t.csv\"\nlatent_path = \"p.csv\"\n",
       {}, "bad.toml", 5, "a trajectory or a latent path, not both"},
      {"latent model without path", obj + "passive = true\nlatent_model = \"m.json\"\n", {}, "bad.toml", 4,
       "only a latent-driven object (latent_path) has a model"},
  };
  for (const BadCase& c : cases) check_rejected(c, "bad.toml");
}

TEST_CASE("scene file: a mesh that cannot be loaded is blamed on the --set that named it (issue 15, defect 4)",
          "[scene]") {
  const SceneDesc s = parse_scene(kScene, "dir/test.toml", {"object.floor.mesh=nothere.mesh"});
  CHECK(s.world.objects[0].mesh_origin.empty());
  CHECK(s.world.objects[1].mesh_origin == "--set object.floor.mesh=nothere.mesh");
  try {
    build_world(s.world);
    FAIL("a missing mesh was loaded");
  } catch (const InputError& e) {
    CHECK(e.file() == "--set object.floor.mesh=nothere.mesh");
    CHECK(e.line() == 0);
    CHECK_THAT(e.what(), Contains("nothere.mesh"));
  }
}

TEST_CASE("scene file: [perturb] globally and per object, and auto*K hash sizes", "[scene][perturb]") {
  const SceneDesc none = parse_scene(kScene, "t.toml");
  CHECK_FALSE(none.perturb.global.any());
  CHECK(none.perturb.objects.empty());
  CHECK(none.collision.cell_size_auto_factor == 1.0);
  CHECK(none.collision.table_size_auto_factor == 1.0);
  const SceneDesc s = parse_scene(kScene, "t.toml",
                                  {"perturb.position=1e-3", "perturb.velocity=0.01", "perturb.rotation=0.02",
                                   "perturb.material=0.1", "object.plate.perturb.velocity=0.5",
                                   "collision.cell_size=auto*0.5", "collision.table_size=auto*4"});
  CHECK(s.perturb.global.position_m == 1e-3);
  CHECK(s.perturb.global.velocity_m_per_s == 0.01);
  CHECK(s.perturb.global.rotation_rad == 0.02);
  CHECK(s.perturb.global.material_rel == 0.1);
  REQUIRE(s.perturb.objects.count("plate") == 1);
  const Jitter plate = s.perturb.objects.at("plate").over(s.perturb.global);
  CHECK(plate.velocity_m_per_s == 0.5);  // its own
  CHECK(plate.position_m == 1e-3);       // the rest inherited
  CHECK(plate.material_rel == 0.1);
  CHECK_FALSE(s.collision.cell_size_m.has_value());
  CHECK(s.collision.cell_size_auto_factor == 0.5);
  CHECK(s.collision.table_size == 0);
  CHECK(s.collision.table_size_auto_factor == 4.0);
  const SceneDesc fixed = parse_scene(kScene, "t.toml", {"collision.table_size=1009"});
  CHECK(fixed.collision.table_size == 1009);
}

TEST_CASE("scene file: a method's settings in [method.NAME], typed by the method's schema", "[scene]") {
  const std::string obj = "[[object]]\nmesh = \"box:size=1x1x1\"\n";
  const SceneDesc s = parse_scene(obj + "[method.every_nth]\nn = 4\n", "m.toml");
  REQUIRE(s.methods.count("every_nth"));
  CHECK(s.methods.at("every_nth").integer("n") == 4);
  CHECK(s.methods.at("every_nth").boolean("hold"));  // the default, filled in
  const SceneDesc set = parse_scene(obj, "m.toml", {"method.every_nth.hold=false"});
  CHECK_FALSE(set.methods.at("every_nth").boolean("hold"));
  CHECK(set.methods.at("every_nth").integer("n") == 2);
  const BadCase cases[] = {
      {"zero", obj + "[method.every_nth]\nn = 0\n", {}, "m.toml", 4, "method.every_nth.n: must lie in [1, 1000000]"},
      {"fraction", obj + "[method.every_nth]\nn = 2.5\n", {}, "m.toml", 4, "method.every_nth.n: must be a whole number"},
      {"wrong type", obj + "[method.every_nth]\nhold = 1\n", {}, "m.toml", 4, "must be true or false"},
      {"unknown key", obj + "[method.every_nth]\nn = 2\nm = 1\n", {}, "m.toml", 5, "unknown key 'm' in method.every_nth"},
      {"unknown method", obj + "[method.every_third]\nn = 2\n", {}, "m.toml", 3, "no method of that name"},
      {"old form", obj + "[every_nth]\nn = 2\n", {}, "m.toml", 3, "go in [method.every_nth]"},
      {"--set", obj, {"method.every_nth.n=0"}, "--set method.every_nth.n=0", 0, "must lie in"},
  };
  for (const BadCase& c : cases) check_rejected(c, "m.toml");
}

TEST_CASE("scene file: collision.response, and implicit response refuses an integrator without a linear step",
          "[scene]") {
  const std::string obj = "[[object]]\nmesh = \"box:size=1x1x1\"\n";
  CHECK(parse_scene(obj, "r.toml").collision.response_mode == ResponseMode::Implicit);  // the default
  CHECK(parse_scene(obj + "[collision]\nresponse = \"explicit\"\n", "r.toml").collision.response_mode ==
        ResponseMode::Explicit);
  check_rejected({"bad mode", obj + "[collision]\nresponse = \"soft\"\n", {}, "r.toml", 4,
                  "collision.response: must be \"implicit\" or \"explicit\""},
                 "r.toml");
  const std::string verlet = obj + "material = { model = \"mass_spring\", integrator = \"verlet\" }\n";
  const SceneDesc s = parse_scene(verlet, "v.toml");
  const World world = build_world(s.world);
  CHECK_THROWS_WITH(resolve_collision_settings(world, s.collision, s.world.dt_s, "v.toml"),
                    Contains("use integrator = \"euler_cromer\" or collision.response = \"explicit\""));
  const SceneDesc explicit_verlet = parse_scene(verlet, "v.toml", {"collision.response=explicit"});
  CHECK_NOTHROW(resolve_collision_settings(world, explicit_verlet.collision, s.world.dt_s, "v.toml"));
  // A resolved cell size whose inverse overflows (a subnormal "auto*K"
  // product) is bad input naming the file, before the hash would refuse it.
  CollisionDesc subnormal = explicit_verlet.collision;
  subnormal.cell_size_m = 1e-310;
  CHECK_THROWS_WITH(resolve_collision_settings(world, subnormal, s.world.dt_s, "v.toml"),
                    Contains("v.toml") && Contains("its inverse is not a finite number"));
}

TEST_CASE("the committed scenes load and build", "[scene]") {
  for (const char* name : {"plates20", "cube_drop"}) {
    INFO(name);
    const SceneDesc s = load_scene_file(resolve_scene(name, default_scene_dirs()));
    const World world = build_world(s.world);
    CHECK(world.bodies.size() == (std::string(name) == "plates20" ? 20u : 1u));
    CHECK(world.ground.has_value());
  }
}

TEST_CASE("resolve_scene: names, paths and clear misses", "[scene]") {
  CHECK(resolve_scene("plates20", default_scene_dirs()).filename() == "plates20.toml");
  CHECK_THROWS_WITH(resolve_scene("nope", default_scene_dirs()), Contains("no scene of that name"));
  CHECK_THROWS_WITH(resolve_scene("missing.toml", default_scene_dirs()), Contains("no such scene file"));
}
