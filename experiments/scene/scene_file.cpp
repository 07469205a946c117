#include "experiments/scene/scene_file.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>

#include "baselines/registry.hpp"
#include "method/handler/method_settings.hpp"
#include "experiments/run/provenance.hpp"
#include "sim/io/atomic_file.hpp"
#include "experiments/scene/method_settings_reader.hpp"
#include "experiments/scene/toml_table_reader.hpp"
#include "sim/io/input_error.hpp"


namespace tcb {
namespace {

Material read_material(TableReader& object, const std::string& context, const Origins& file) {
  Material m;
  const toml::table* table = object.table("material");
  if (!table) return m;
  TableReader r(*table, context + ".material", file);
  if (const auto model = r.string("model")) {
    if (*model == "corotational_fem") {
      m.model = MaterialModel::CorotationalFem;
    } else if (*model == "mass_spring") {
      m.model = MaterialModel::MassSpring;
      m.integrator = Integrator::EulerCromer;
    } else {
      r.fail("model", "must be \"corotational_fem\" or \"mass_spring\", not \"" + *model + "\"");
    }
  }
  if (const auto integrator = r.string("integrator")) {
    const bool fem = m.model == MaterialModel::CorotationalFem;
    if (fem && *integrator != "implicit_euler")
      r.fail("integrator", "corotational_fem integrates with \"implicit_euler\" only");
    if (!fem && *integrator == "euler_cromer")
      m.integrator = Integrator::EulerCromer;
    else if (!fem && *integrator == "verlet")
      m.integrator = Integrator::VelocityVerlet;
    else if (!fem)
      r.fail("integrator", "mass_spring integrates with \"euler_cromer\" or \"verlet\"");
  }
  m.youngs_modulus_pa = r.positive("youngs_modulus", m.youngs_modulus_pa);
  if (const auto nu = r.number("poisson_ratio")) {
    if (!(*nu > -1.0 && *nu < 0.5)) r.fail("poisson_ratio", "must lie strictly between -1 and 0.5");
    m.poisson_ratio = *nu;
  }
  m.density_kg_per_m3 = r.positive("density", m.density_kg_per_m3);
  m.damping_mass_per_s = r.non_negative("damping_mass", m.damping_mass_per_s);
  m.damping_stiffness_s = r.non_negative("damping_stiffness", m.damping_stiffness_s);
  m.cg_tolerance = r.positive("cg_tolerance", m.cg_tolerance);
  m.cg_max_iterations = static_cast<int>(r.integer("cg_max_iterations", 1, 100000).value_or(m.cg_max_iterations));
  r.finish();
  return m;
}

/// "auto" (1) or "auto*K" (K, finite and > 0); nullopt for anything else.
std::optional<double> auto_factor(const std::string& text) {
  if (text == "auto") return 1.0;
  if (text.rfind("auto*", 0) != 0 || text.size() == 5) return std::nullopt;
  const std::string k = text.substr(5);
  char* end = nullptr;
  const double factor = std::strtod(k.c_str(), &end);
  if (end != k.c_str() + k.size() || !(factor > 0.0) || !std::isfinite(factor)) return std::nullopt;
  return factor;
}

/// A [perturb] table, global or an object's: the keys it sets.
JitterOverride read_jitter(const toml::table& table, const std::string& context, const Origins& file) {
  TableReader r(table, context, file);
  JitterOverride j;
  if (r.number("position")) j.position_m = r.non_negative("position", 0.0);
  if (r.number("velocity")) j.velocity_m_per_s = r.non_negative("velocity", 0.0);
  if (r.number("rotation")) j.rotation_rad = r.non_negative("rotation", 0.0);
  if (r.number("material")) {
    j.material_rel = r.non_negative("material", 0.0);
    if (!(*j.material_rel < 1.0)) r.fail("material", "must be below 1 (Young's modulus is scaled by 1 + material * u, u in [-1, 1))");
  }
  r.finish();
  return j;
}

ObjectDesc read_object(const toml::table& table, std::size_t index, const std::filesystem::path& path,
                       const Origins& file, Perturbation& perturb) {
  ObjectDesc o;
  TableReader r(table, "object[" + std::to_string(index) + "]", file);
  o.source_line = where_of(table, file).line;
  o.name = r.string("name").value_or("object" + std::to_string(index));
  if (o.name.empty()) r.fail("name", "must not be empty");
  const std::string context = "object '" + o.name + "'";
  TableReader named(table, context, file);  // errors below name the object
  const auto mesh = named.string("mesh");
  if (!mesh) throw InputError(file.file, o.source_line, context + " has no mesh (a file or a generator such as \"box:size=1x0.1x1,cells=8x1x8\")");
  o.mesh = *mesh;
  if (const Where w = where_of(*named.node("mesh"), file); w.file != file.file) o.mesh_origin = w.file;
  o.base_dir = path.parent_path();
  o.position_m = named.vec3("position").value_or(o.position_m);
  o.scale = named.positive("scale", o.scale);
  o.velocity_m_per_s = named.vec3("velocity").value_or(o.velocity_m_per_s);
  o.passive = named.boolean("passive").value_or(false);
  if (const auto trajectory = named.string("trajectory")) {
    if (!o.passive) named.fail("trajectory", "a driven object must be passive = true");
    if (named.vec3("position")) named.fail("position", "a driven object's position comes from its trajectory");
    o.trajectory = *trajectory;
  }
  if (const auto latent_path = named.string("latent_path")) {
    if (!o.passive) named.fail("latent_path", "a latent-driven object must be passive = true");
    if (!o.trajectory.empty()) named.fail("latent_path", "an object follows a trajectory or a latent path, not both");
    if (o.mesh.rfind("finger:", 0) != 0)
      named.fail("latent_path", "needs a latent family as the mesh (\"finger:finger_small\" or \"finger:finger_large\")");
    o.latent_path = *latent_path;
  }
  if (const auto model = named.string("latent_model")) {
    if (o.latent_path.empty()) named.fail("latent_model", "only a latent-driven object (latent_path) has a model");
    o.latent_model = *model;
  }
  o.self_collision = named.boolean("self_collision").value_or(false);
  named.node("name");
  o.material = read_material(named, context, file);
  if (const toml::table* stack = named.table("stack")) {
    TableReader s(*stack, context + ".stack", file);
    o.stack.count = static_cast<int>(s.integer("count", 1, 100000).value_or(1));
    if (const auto axis = s.string("axis")) {
      if (*axis == "x") o.stack.axis = 0;
      else if (*axis == "y") o.stack.axis = 1;
      else if (*axis == "z") o.stack.axis = 2;
      else s.fail("axis", "must be \"x\", \"y\" or \"z\"");
    }
    o.stack.gap_m = s.non_negative("gap", 0.0);
    o.stack.stagger_m = s.vec3("stagger").value_or(Vec3::Zero());
    if (o.stack.stagger_m[o.stack.axis] != 0.0) s.fail("stagger", "must be 0 along the stacking axis");
    // A driven body's position comes from its path, so its copies would all
    // be one body in one place; the world builder would make only one.
    if (o.stack.count > 1 && (!o.trajectory.empty() || !o.latent_path.empty()))
      s.fail("count", "a driven object (trajectory or latent_path) cannot be stacked");
    s.finish();
  }
  if (const toml::table* p = named.table("perturb")) {
    if (o.passive) named.fail("perturb", "passive objects are not perturbed (a driven object follows its trajectory, a fixed one is the scene's frame)");
    perturb.objects[o.name] = read_jitter(*p, context + ".perturb", file);
  }
  named.finish();
  return o;
}

// ---- --set overrides -------------------------------------------------------

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  return parts;
}

void apply_override(toml::table& root, const std::string& assignment, Origins& origins) {
  const std::string origin = "--set " + assignment;
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(origin, 0, "expected key=value");
  const std::vector<std::string> keys = split_path(assignment.substr(0, eq));
  const std::string value_text = assignment.substr(eq + 1);
  for (const auto& k : keys)
    if (k.empty()) throw InputError(origin, 0, "empty key segment");

  // The value, parsed as TOML; a bare word falls back to a string.
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + value_text, origin);
  } catch (const toml::parse_error&) {
    try {
      parsed = toml::parse("value = " + format_setting(SettingValue(value_text)), origin);  // a TOML string
    } catch (const toml::parse_error& e) {
      throw InputError(origin, 0, std::string(e.description()));
    }
  }
  toml::node& value = *parsed.get("value");

  toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    toml::node* next = table->get(keys[i]);
    if (next && next->is_array()) {  // [[object]]: select by name or index
      toml::array& array = *next->as_array();
      const std::string& selector = keys[++i];
      toml::table* found = nullptr;
      for (std::size_t k = 0; k < array.size(); ++k) {
        toml::table* element = array[k].as_table();
        if (!element) continue;
        const auto name = (*element)["name"].value<std::string>();
        if ((name && *name == selector) || selector == std::to_string(k)) found = element;
      }
      if (!found) throw InputError(origin, 0, "no " + keys[i - 1] + " named or numbered '" + selector + "'");
      table = found;
      if (i + 1 >= keys.size()) throw InputError(origin, 0, "the path ends at a whole " + keys[i - 1]);
      continue;
    }
    if (!next) {  // a table the override makes: its errors are the override's
      next = &table->insert_or_assign(keys[i], toml::table{}).first->second;
      origins.overridden[next] = origin;
    }
    if (!next->is_table()) throw InputError(origin, 0, "'" + keys[i] + "' is not a table");
    table = next->as_table();
  }
  value.visit([&](auto& concrete) { table->insert_or_assign(keys.back(), concrete); });
  // The value and everything nested in it (an inline table's keys, an
  // array's elements, at any depth) come from the override.
  const auto mark = [&](auto&& self, toml::node& node) -> void {
    origins.overridden[&node] = origin;
    if (toml::array* array = node.as_array())
      for (toml::node& element : *array) self(self, element);
    if (toml::table* inner = node.as_table())
      for (auto&& [key, child] : *inner) self(self, child);
  };
  mark(mark, *table->get(keys.back()));
}

}  // namespace

SceneDesc parse_scene(const std::string& text, const std::filesystem::path& path,
                      const std::vector<std::string>& overrides) {
  Origins file{path.string(), {}};
  toml::table root;
  try {
    root = toml::parse(text, file.file);
  } catch (const toml::parse_error& e) {
    throw InputError(file.file, static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
  for (const std::string& o : overrides) apply_override(root, o, file);

  SceneDesc scene;
  scene.path = path;
  scene.world.path = path;
  scene.name = path.stem().string();
  TableReader top(root, "scene file", file);
  for (const MethodInfo& m : method_registry())  // the form before [method.NAME]
    if (top.node(m.name)) top.fail(m.name, "a method's settings go in [method." + m.name + "]");
  if (const toml::table* s = top.table("scene")) {
    TableReader r(*s, "scene", file);
    scene.name = r.string("name").value_or(scene.name);
    // It names result directories (`tcbench run`'s default --out).
    if (scene.name.empty() || scene.name == "." || scene.name == ".." ||
        scene.name.find_first_of("/\\") != std::string::npos)
      r.fail("name", "must be a non-empty name without '/' or '\\', not '.' or '..' (it names result directories)");
    r.string("description");
    scene.world.dt_s = r.positive("dt", scene.world.dt_s);
    scene.steps = r.integer("steps", 0, std::int64_t(1) << 40).value_or(scene.steps);
    scene.world.gravity_m_per_s2 = r.vec3("gravity").value_or(scene.world.gravity_m_per_s2);
    scene.max_speed_m_per_s = r.positive("max_speed", scene.max_speed_m_per_s);
    scene.max_energy_gain = r.positive("max_energy_gain", scene.max_energy_gain);
    if (const auto order = r.string("mesh_order")) {
      if (*order == "file") scene.world.mesh_order = MeshOrder::File;
      else if (*order == "curve") scene.world.mesh_order = MeshOrder::Curve;
      else r.fail("mesh_order", "is '" + *order + "'; must be \"file\" (the file's vertex numbering) or \"curve\" "
                                "(renumbered along a Morton curve at load)");
    }
    r.finish();
  }
  if (const toml::table* g = top.table("ground")) {
    TableReader r(*g, "ground", file);
    GroundPlane ground;
    ground.height_m = r.number("height").value_or(0.0);
    ground.friction = r.non_negative("friction", ground.friction);
    r.finish();
    scene.world.ground = ground;
  }
  if (const toml::table* c = top.table("collision")) {
    TableReader r(*c, "collision", file);
    if (const toml::node* cell = r.node("cell_size")) {
      if (cell->is_string()) {
        const auto factor = auto_factor(*cell->value<std::string>());
        if (!factor) r.fail("cell_size", "must be \"auto\", \"auto*K\" (K > 0 times the mean tet edge) or a positive length");
        scene.collision.cell_size_m.reset();
        scene.collision.cell_size_auto_factor = *factor;
      } else {
        const auto size = r.number("cell_size");
        if (!(*size > 0.0) || !std::isfinite(1.0 / *size))
          r.fail("cell_size", "must be \"auto\", \"auto*K\" or a positive length (not so small that its inverse overflows)");
        scene.collision.cell_size_m = size;
      }
    }
    if (const auto hash = r.string("hash")) {
      if (*hash == "mixed") scene.collision.hash = HashFunction::Mixed;
      else if (*hash == "paper") scene.collision.hash = HashFunction::Paper;
      else r.fail("hash", "must be \"mixed\" or \"paper\"");
    }
    if (const toml::node* table = r.node("table_size"); table && table->is_string()) {
      const auto factor = auto_factor(*table->value<std::string>());
      if (!factor) r.fail("table_size", "must be \"auto\", \"auto*K\" (the next prime above 2 K tets + 1) or a whole number of buckets");
      scene.collision.table_size = 0;
      scene.collision.table_size_auto_factor = *factor;
    } else {
      scene.collision.table_size =
          static_cast<std::size_t>(r.integer("table_size", 0, std::int64_t(1) << 32).value_or(0));
    }
    scene.collision.response_stiffness_n_per_m =
        r.non_negative("response_stiffness", scene.collision.response_stiffness_n_per_m);
    scene.collision.damping_n_s_per_m = r.non_negative("damping", scene.collision.damping_n_s_per_m);
    scene.collision.friction = r.non_negative("friction", scene.collision.friction);
    scene.collision.threads = static_cast<int>(r.integer("threads", 1, 64).value_or(1));
    if (const auto response = r.string("response")) {
      if (*response == "implicit") scene.collision.response_mode = ResponseMode::Implicit;
      else if (*response == "explicit") scene.collision.response_mode = ResponseMode::Explicit;
      else r.fail("response", "must be \"implicit\" or \"explicit\"");
    }
    if (const toml::node* pairs = r.node("pair")) {
      const toml::array* array = pairs->as_array();
      if (!array || !array->is_array_of_tables()) r.fail("pair", "must be an array of tables: write [[collision.pair]]");
      for (std::size_t i = 0; i < array->size(); ++i) {
        const toml::table& t = *(*array)[i].as_table();
        TableReader pr(t, "collision.pair[" + std::to_string(i) + "]", file);
        CollisionPairDesc pair;
        pair.source_line = where_of(t, file).line;
        const toml::node* names = pr.node("objects");
        const toml::array* list = names ? names->as_array() : nullptr;
        if (!list || list->size() != 2 || !(*list)[0].is_string() || !(*list)[1].is_string())
          pr.fail("objects", "must name two objects: objects = [\"a\", \"b\"]");
        pair.a = *(*list)[0].value<std::string>();
        pair.b = *(*list)[1].value<std::string>();
        if (const auto v = pr.number("response_stiffness")) pair.stiffness_n_per_m = pr.non_negative("response_stiffness", *v);
        if (const auto v = pr.number("damping")) pair.damping_n_s_per_m = pr.non_negative("damping", *v);
        if (const auto v = pr.number("friction")) pair.friction = pr.non_negative("friction", *v);
        pr.finish();
        scene.collision.pairs.push_back(pair);
      }
    }
    r.finish();
  }
  if (const toml::table* m = top.table("metrics")) {
    TableReader r(*m, "metrics", file);
    if (const auto jitter = r.string("jitter")) {
      if (*jitter != "vertical_velocity_rms") r.fail("jitter", "must be \"vertical_velocity_rms\"");
      scene.jitter_measure = *jitter;
    }
    r.finish();
  }
  if (const toml::table* p = top.table("perturb")) scene.perturb.global = read_jitter(*p, "perturb", file).over(scene.perturb.global);
  if (const toml::table* methods = top.table("method")) {
    TableReader all(*methods, "method", file);
    for (auto&& [key, node] : *methods) {
      const std::string name(key.str());
      const MethodInfo* info = nullptr;
      for (const MethodInfo& m : method_registry())
        if (m.name == name) info = &m;
      if (!info) all.fail(name, "no method of that name (`tcbench list methods`)");
      const toml::table* t = all.table(name);
      TableReader r(*t, "method." + name, file);
      scene.methods[name] = read_method_settings(r, *info);
      r.finish();
    }
  }
  if (const toml::node* objects = top.node("object")) {
    const toml::array* array = objects->as_array();
    if (!array || !array->is_array_of_tables())
      top.fail("object", "must be an array of tables: write [[object]]");
    // Objects' and bodies' names share one namespace: --set and [perturb]
    // select objects by name, pairs name bodies or the object a stack was
    // made from, and the results name bodies, so no name may mean two things.
    std::map<std::string, std::string> taken;  // name -> what it names
    for (std::size_t i = 0; i < array->size(); ++i) {
      ObjectDesc o = read_object(*(*array)[i].as_table(), i, path, file, scene.perturb);
      std::vector<std::pair<std::string, std::string>> names = {{o.name, "object '" + o.name + "'"}};
      if (o.stack.count > 1)
        for (const std::string& body : body_names(o.name, o.stack))
          names.emplace_back(body, "a body of the stack '" + o.name + "'");
      for (const auto& [name, what] : names) {
        const auto [it, added] = taken.emplace(name, what);
        if (added) continue;
        if (it->second == what)
          throw InputError(file.file, o.source_line, "two objects are named '" + o.name + "'");
        throw InputError(file.file, o.source_line,
                         "the name '" + name + "' is both " + it->second + " and " + what +
                             " (a stack of N > 1 makes bodies NAME_00 .. NAME_{N-1}; all names must differ)");
      }
      scene.world.objects.push_back(std::move(o));
    }
  }
  top.finish();
  if (scene.world.objects.empty()) throw InputError(file.file, 0, "the scene has no [[object]]");
  return scene;
}

SceneDesc load_scene_file(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_file(path), path, overrides);
}

std::vector<std::filesystem::path> default_scene_dirs() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("TCBENCH_SCENES")) {
    std::stringstream in(env);
    for (std::string dir; std::getline(in, dir, ':');)
      if (!dir.empty()) dirs.emplace_back(dir);
  }
  dirs.emplace_back(source_tree_dir() / "experiments" / "scenes");
  return dirs;
}

std::filesystem::path resolve_scene(const std::string& scene, const std::vector<std::filesystem::path>& dirs) {
  const std::filesystem::path direct(scene);
  if (direct.extension() == ".toml") {
    if (!std::filesystem::exists(direct)) throw InputError(scene, 0, "no such scene file");
    return direct;
  }
  for (const auto& dir : dirs)
    if (std::filesystem::exists(dir / (scene + ".toml"))) return dir / (scene + ".toml");
  std::string searched;
  for (const auto& dir : dirs) {
    searched += ' ';
    searched += dir.string();
  }
  throw InputError(scene, 0, "no scene of that name (searched:" + searched + "; `tcbench list scenes` lists them)");
}

}  // namespace tcb
