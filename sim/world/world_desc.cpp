#include "sim/world/world_desc.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "sim/io/input_error.hpp"
#include "sim/latent/latent_path.hpp"
#include "sim/mesh/curve_numbering.hpp"
#include "sim/mesh/load_mesh.hpp"

namespace tcb {
namespace {

constexpr const char* kFingerPrefix = "finger:";

// The skinned finger of a "finger:PRESET" mesh; InputError listing the presets otherwise.
std::shared_ptr<const SkinnedFinger> finger_of(const ObjectDesc& object) {
  const std::string preset = object.mesh.substr(std::string(kFingerPrefix).size());
  try {
    return std::make_shared<const SkinnedFinger>(finger_preset(preset));
  } catch (const std::invalid_argument& e) {
    throw InputError(object.mesh, 0, e.what());
  }
}

std::shared_ptr<const TetMesh> load_cached(const ObjectDesc& object, const WorldDesc& desc,
                                           std::map<std::string, std::shared_ptr<const TetMesh>>& cache) {
  const std::string key = (object.base_dir / object.mesh).lexically_normal().string();
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  try {
    if (object.mesh.rfind(kFingerPrefix, 0) == 0) return finger_of(object)->mesh();
    TetMesh loaded = load_mesh(object.mesh, object.base_dir);
    if (desc.mesh_order == MeshOrder::Curve) loaded = vertices_along_curve(loaded);
    auto mesh = std::make_shared<const TetMesh>(std::move(loaded));
    cache.emplace(key, mesh);
    return mesh;
  } catch (const InputError& e) {
    if (e.line() > 0 || (desc.path.empty() && object.mesh_origin.empty())) throw;  // the mesh file's line says more
    // Blame where the mesh was named: the scene's object, or the --set that replaced it.
    if (!object.mesh_origin.empty()) throw InputError(object.mesh_origin, 0, "object '" + object.name + "': " + e.what());
    throw InputError(desc.path.string(), object.source_line, "object '" + object.name + "': " + e.what());
  }
}

Body make_body(const std::string& name, const ObjectDesc& object, std::shared_ptr<const TetMesh> mesh,
               std::vector<Vec3> x) {
  Body body;
  body.name = name;
  body.group = object.name;
  body.mesh = std::move(mesh);
  body.v_m_per_s.assign(x.size(), object.velocity_m_per_s);
  body.contact_force_n.assign(x.size(), Vec3::Zero());
  body.mass_kg = lumped_masses_kg(*body.mesh, x, object.material.density_kg_per_m3);
  body.material = object.material;
  body.passive = object.passive;
  body.self_collision = object.self_collision;
  if (!object.passive) body.model = make_elastic_model(*body.mesh, x, object.material);
  else body.v_m_per_s.assign(x.size(), Vec3::Zero());
  body.x_m = std::move(x);
  return body;
}

// What a mesh brings that a run should know about, said once per object; an
// object that would have no mass at all is refused (nothing to simulate).
void check_object(World& world, const WorldDesc& desc, const ObjectDesc& object, const TetMesh& mesh,
                  const std::vector<Vec3>& scaled) {
  const std::string who = fmt::format("object '{}' (mesh {})", object.name, object.mesh);
  if (mesh.inverted_tets > 0)
    world.build_warnings.push_back(fmt::format("{}: {} of {} tets were given inverted (negative orientation) and "
                                               "are simulated reoriented", who, mesh.inverted_tets, mesh.tet_count()));
  if (mesh.degenerate_tets > 0)
    world.build_warnings.push_back(fmt::format("{}: {} of {} tets are exactly flat: they get no mass and no "
                                               "stiffness", who, mesh.degenerate_tets, mesh.tet_count()));
  if (object.passive) return;
  const std::vector<double> mass = lumped_masses_kg(mesh, scaled, object.material.density_kg_per_m3);
  double total = 0.0;
  std::size_t massless = 0;
  for (double m : mass) {
    total += m;
    massless += !(m > 0.0);
  }
  if (!(total > 0.0) || !std::isfinite(total))
    throw InputError(desc.path.empty() ? object.name : desc.path.string(), object.source_line,
                     fmt::format("{}: no mass to simulate ({}): every tet is flat, or scale {} and density {} "
                                 "kg/m^3 make the volumes {}",
                                 who, total, object.scale, object.material.density_kg_per_m3,
                                 std::isfinite(total) ? "underflow to 0" : "overflow"));
  if (massless > 0)
    world.build_warnings.push_back(fmt::format("{}: {} of {} vertices have no mass (every tet around them is flat "
                                               "or none uses them): they stay where they are",
                                               who, massless, mass.size()));
}

// A body driven along a latent path: at its path's first code, not the rest mesh.
Body make_latent_body(const WorldDesc& desc, const ObjectDesc& object, std::shared_ptr<const TetMesh> mesh) {
  const auto blame = [&](const std::string& what) {
    throw InputError(desc.path.empty() ? object.name : desc.path.string(), object.source_line,
                     "object '" + object.name + "': " + what);
  };
  if (object.mesh.rfind(kFingerPrefix, 0) != 0)
    blame("latent_path needs a latent family as its mesh (\"finger:finger_small\" or \"finger:finger_large\"), not '" +
          object.mesh + "'");
  auto drive = std::make_shared<LatentDrive>();
  drive->family = object.mesh.substr(std::string(kFingerPrefix).size());
  drive->finger = finger_of(object);
  drive->scale = object.scale;
  drive->position_m = object.position_m;
  if (!object.latent_model.empty()) drive->model_path = (object.base_dir / object.latent_model).lexically_normal();
  try {
    drive->path = read_latent_path_csv(object.base_dir / object.latent_path, drive->finger->latent_size());
  } catch (const InputError& e) {
    if (e.line() > 0 || desc.path.empty()) throw;
    blame(e.what());
  }
  Body body = make_body(object.name, object, std::move(mesh), drive->positions_m(drive->path.at(0.0)));
  body.latent_code = drive->path.at(0.0);
  body.latent = std::move(drive);
  return body;
}

}  // namespace

std::vector<std::string> body_names(const std::string& object_name, const StackDesc& stack) {
  if (stack.count <= 1) return {object_name};
  std::vector<std::string> names;
  for (int copy = 0; copy < stack.count; ++copy) names.push_back(fmt::format("{}_{:02d}", object_name, copy));
  return names;
}

World build_world(const WorldDesc& desc) {
  World world;
  world.gravity_m_per_s2 = desc.gravity_m_per_s2;
  world.ground = desc.ground;
  std::map<std::string, std::shared_ptr<const TetMesh>> cache;
  for (const ObjectDesc& object : desc.objects) {
    const auto mesh = load_cached(object, desc, cache);
    std::vector<Vec3> scaled(mesh->positions_m.size());
    for (std::size_t i = 0; i < scaled.size(); ++i) scaled[i] = object.scale * mesh->positions_m[i];
    // Coordinates beyond the exact predicates' range (orient3d.hpp: products
    // of three differences must stay normal doubles) are bad input, said here
    // with the object's line, not later as a hash that cannot size its cells.
    for (const Vec3& p : scaled)
      if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinate_m)
        throw InputError(desc.path.empty() ? object.name : desc.path.string(), object.source_line,
                         fmt::format("object '{}': scale {} puts its coordinates beyond {:g} m, the range of the "
                                     "exact geometric predicates",
                                     object.name, object.scale, kMaxCoordinate_m));
    check_object(world, desc, object, *mesh, scaled);
    if (!object.latent_path.empty()) {
      world.bodies.push_back(make_latent_body(desc, object, mesh));
      continue;
    }
    if (!object.trajectory.empty()) {
      std::shared_ptr<const Trajectory> path;
      try {
        path = std::make_shared<const Trajectory>(read_trajectory_csv(object.base_dir / object.trajectory));
      } catch (const InputError& e) {
        if (e.line() > 0 || desc.path.empty()) throw;
        throw InputError(desc.path.string(), object.source_line, "object '" + object.name + "': " + e.what());
      }
      std::vector<Vec3> x(scaled);
      for (Vec3& p : x) p += path->at(0.0);
      Body body = make_body(object.name, object, mesh, std::move(x));
      body.trajectory = std::move(path);
      body.shape_m = std::move(scaled);
      world.bodies.push_back(std::move(body));
      continue;
    }
    if (object.stack.count <= 1) {
      for (Vec3& p : scaled) p += object.position_m;
      world.bodies.push_back(make_body(object.name, object, mesh, std::move(scaled)));
      continue;
    }
    const int axis = object.stack.axis;
    double lowest = scaled.empty() ? 0.0 : scaled[0][axis], highest = lowest;
    for (const Vec3& p : scaled) {
      lowest = std::min(lowest, p[axis]);
      highest = std::max(highest, p[axis]);
    }
    for (Vec3& p : scaled) p[axis] -= lowest;  // the lowest coordinate becomes exactly 0
    const double step = (highest - lowest) + object.stack.gap_m;
    Vec3 offset = object.position_m;
    const std::vector<std::string> names = body_names(object.name, object.stack);
    for (int copy = 0; copy < object.stack.count; ++copy) {
      std::vector<Vec3> x(scaled);
      const Vec3 shift = copy % 2 ? Vec3(offset + object.stack.stagger_m) : offset;
      for (Vec3& p : x) p += shift;
      world.bodies.push_back(make_body(names[static_cast<std::size_t>(copy)], object, mesh, std::move(x)));
      offset[axis] += step;
    }
  }
  return world;
}

}  // namespace tcb
