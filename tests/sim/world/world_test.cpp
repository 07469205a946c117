// The world: a cube settles on the ground and stays; passive bodies stay put;
// stacks touch exactly; ground friction; stability at the extremes;
// degenerate objects said or refused.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

#include "sim/io/atomic_file.hpp"
#include "sim/mesh/curve_numbering.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;

namespace {

WorldDesc cube_on_ground(double size_m, double youngs_pa, double dt_s, MaterialModel model, Integrator integrator) {
  WorldDesc scene;
  scene.dt_s = dt_s;
  scene.ground = GroundPlane{0.0, 0.5};
  ObjectDesc cube;
  cube.name = "cube";
  cube.mesh = "box:size=" + std::to_string(size_m) + "x" + std::to_string(size_m) + "x" + std::to_string(size_m) +
              ",cells=3x3x3";
  cube.position_m = Vec3(0.0, size_m / 2.0, 0.0);  // resting on the ground
  cube.material.model = model;
  cube.material.integrator = integrator;
  cube.material.youngs_modulus_pa = youngs_pa;
  cube.material.damping_mass_per_s = 1.0;
  scene.objects.push_back(cube);
  return scene;
}

Vec3 centre(const Body& b) { return centre_of_mass_m(b); }

double lowest_y(const Body& b) {
  double y = b.x_m[0].y();
  for (const Vec3& p : b.x_m) y = std::min(y, p.y());
  return y;
}

}  // namespace

TEST_CASE("a cube resting on the ground settles and stays for 1000 steps", "[world]") {
  const double size = 0.1;
  World world = build_world(cube_on_ground(size, 1e5, 1e-3, MaterialModel::CorotationalFem, Integrator::ImplicitEuler));
  for (int s = 0; s < 300; ++s) world.step(1e-3);  // settle under its own weight
  const Vec3 settled = centre(world.bodies[0]);
  for (int s = 0; s < 1000; ++s) {
    world.step(1e-3);
    const Vec3 c = centre(world.bodies[0]);
    REQUIRE((c - settled).norm() < 1e-3 * size);
    REQUIRE(lowest_y(world.bodies[0]) >= 0.0);
  }
  CHECK(world.max_speed_m_per_s() < 1e-3);
  CHECK(settled.y() < size / 2.0);         // it sagged a little under gravity
  CHECK(settled.y() > 0.45 * size);        // but not much: E = 1e5 Pa
}

TEST_CASE("passive bodies are not integrated", "[world]") {
  WorldDesc scene;
  ObjectDesc wall;
  wall.name = "wall";
  wall.mesh = "box:size=1x1x1,cells=1x1x1";
  wall.passive = true;
  wall.velocity_m_per_s = Vec3(1, 2, 3);
  scene.objects.push_back(wall);
  World world = build_world(scene);
  REQUIRE(world.bodies[0].model == nullptr);
  const std::vector<Vec3> before = world.bodies[0].x_m;
  for (int s = 0; s < 10; ++s) world.step(1e-2);
  CHECK(world.bodies[0].x_m == before);
  CHECK(world.kinetic_energy_j() == 0.0);
}

TEST_CASE("stacked copies touch exactly, face on face", "[world]") {
  WorldDesc scene;
  ObjectDesc plate;
  plate.name = "plate";
  plate.mesh = "box:size=0.3x0.0137x0.3,cells=3x1x3";  // a thickness with no exact binary form
  plate.position_m = Vec3(0.1, 0.0123, -0.2);
  plate.stack.count = 20;
  scene.objects.push_back(plate);
  const World world = build_world(scene);
  REQUIRE(world.bodies.size() == 20);
  CHECK(world.bodies[0].name == "plate_00");
  CHECK(world.bodies[19].name == "plate_19");
  for (std::size_t i = 0; i + 1 < world.bodies.size(); ++i) {
    double top = -1e9, bottom = 1e9;
    for (const Vec3& p : world.bodies[i].x_m) top = std::max(top, p.y());
    for (const Vec3& p : world.bodies[i + 1].x_m) bottom = std::min(bottom, p.y());
    REQUIRE(top == bottom);  // bit for bit
    // and every top vertex of plate i coincides with a bottom vertex of plate i+1
    int coincident = 0;
    for (const Vec3& p : world.bodies[i].x_m)
      for (const Vec3& q : world.bodies[i + 1].x_m) coincident += p == q;
    REQUIRE(coincident == 16);
  }
  CHECK(world.bodies[0].x_m[0].y() == 0.0123);
}

TEST_CASE("ground friction stops a sliding block; without friction it slides", "[world]") {
  for (double mu : {0.0, 0.8}) {
    WorldDesc scene = cube_on_ground(0.1, 1e5, 1e-3, MaterialModel::CorotationalFem, Integrator::ImplicitEuler);
    scene.ground->friction = mu;
    scene.objects[0].velocity_m_per_s = Vec3(1.0, 0.0, 0.0);
    scene.objects[0].material.damping_mass_per_s = 0.0;
    World world = build_world(scene);
    for (int s = 0; s < 500; ++s) world.step(1e-3);
    const double vx = world.bodies[0].v_m_per_s[0].x();
    if (mu == 0.0)
      CHECK(vx > 0.9);
    else
      CHECK(std::abs(vx) < 1e-3);  // mu g t = 3.9 m/s of braking available
  }
}

TEST_CASE("dynamics stay finite at the extremes", "[world][extremes]") {
  struct Case {
    const char* name;
    double size_m, youngs_pa, dt_s;
    MaterialModel model;
    Integrator integrator;
  };
  const Case cases[] = {
      {"tiny 1 mm cube", 1e-3, 1e5, 1e-4, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"huge 100 m cube", 1e2, 1e7, 1e-2, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"stiff 1 GPa", 0.1, 1e9, 1e-3, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"soft 100 Pa", 0.1, 1e2, 1e-3, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"small step 1e-5 s", 0.1, 1e5, 1e-5, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"large step 1e-2 s", 0.1, 1e5, 1e-2, MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
      {"mass-spring Euler-Cromer", 0.1, 1e4, 1e-4, MaterialModel::MassSpring, Integrator::EulerCromer},
      {"mass-spring Verlet", 0.1, 1e4, 1e-4, MaterialModel::MassSpring, Integrator::VelocityVerlet},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    WorldDesc scene = cube_on_ground(c.size_m, c.youngs_pa, c.dt_s, c.model, c.integrator);
    scene.objects[0].position_m.y() += c.size_m;  // dropped from one size up
    World world = build_world(scene);
    for (int s = 0; s < 300; ++s) world.step(c.dt_s);
    REQUIRE(std::isfinite(world.max_speed_m_per_s()));
    CHECK(lowest_y(world.bodies[0]) >= 0.0);
    CHECK(centre(world.bodies[0]).y() > 0.0);
  }
}

TEST_CASE("a heavy body on a light one: 1000:1 mass ratio stays finite", "[world][extremes]") {
  WorldDesc scene = cube_on_ground(0.1, 1e5, 1e-3, MaterialModel::CorotationalFem, Integrator::ImplicitEuler);
  ObjectDesc heavy = scene.objects[0];
  heavy.name = "heavy";
  heavy.material.density_kg_per_m3 = 1.0e6;
  heavy.position_m = Vec3(0.5, 0.05, 0.0);
  scene.objects.push_back(heavy);
  World world = build_world(scene);
  const double ratio = world.bodies[1].mass_kg[0] / world.bodies[0].mass_kg[0];
  CHECK(ratio == Approx(1000.0));
  for (int s = 0; s < 300; ++s) world.step(1e-3);
  CHECK(std::isfinite(world.max_speed_m_per_s()));
}

TEST_CASE("a cloned world steps bit for bit like the original", "[world][clone]") {
  // Every kind of state: FEM (warm-started rotations) and mass-spring bodies,
  // a passive body, pending contact forces and an implicit contact link.
  for (const auto& [model, integrator] : std::vector<std::pair<MaterialModel, Integrator>>{
           {MaterialModel::CorotationalFem, Integrator::ImplicitEuler},
           {MaterialModel::MassSpring, Integrator::VelocityVerlet},
           {MaterialModel::MassSpring, Integrator::EulerCromer}}) {
    WorldDesc desc = cube_on_ground(0.1, 1e5, 1e-3, model, integrator);
    ObjectDesc upper = desc.objects[0];
    upper.name = "upper";
    upper.position_m = Vec3(0.02, 0.2, 0.01);
    desc.objects.push_back(upper);
    ObjectDesc wall = desc.objects[0];
    wall.name = "wall";
    wall.passive = true;
    wall.position_m = Vec3(0.5, 0.05, 0.0);
    desc.objects.push_back(wall);
    World original = build_world(desc);
    for (int s = 0; s < 20; ++s) original.step(desc.dt_s);  // warm starts that differ from the rest state
    const auto load = [&, integrator = integrator](World& w) {
      w.bodies[1].contact_force_n[3] = Vec3(0.1, -0.2, 0.05);
      if (integrator != Integrator::ImplicitEuler) return;  // links need a linear step
      ContactLink link;
      link.point_body = 1;
      link.vertex = 0;
      link.tet_body = 0;
      link.tet_vertices = {0, 1, 2, 3};
      link.weights = {0.25, 0.25, 0.25, 0.25};
      link.normal = Vec3(0, 1, 0);
      link.depth_m = 1e-3;
      link.stiffness_n_per_m = 100.0;
      w.contact_links.push_back(link);
    };
    load(original);
    World copy = clone_world(original);
    for (int s = 0; s < 30; ++s) {
      original.step(desc.dt_s);
      copy.step(desc.dt_s);
      if (s % 10 == 0) {
        load(original);
        load(copy);
      }
    }
    CHECK(copy.time_s == original.time_s);
    CHECK(copy.step_index == original.step_index);
    for (std::size_t b = 0; b < original.bodies.size(); ++b) {
      INFO("body " << b);
      for (std::size_t v = 0; v < original.bodies[b].x_m.size(); ++v) {
        REQUIRE(copy.bodies[b].x_m[v] == original.bodies[b].x_m[v]);
        REQUIRE(copy.bodies[b].v_m_per_s[v] == original.bodies[b].v_m_per_s[v]);
        REQUIRE(copy.bodies[b].applied_contact_force_n[v] == original.bodies[b].applied_contact_force_n[v]);
      }
    }
  }
}

TEST_CASE("degenerate objects: inverted tets reoriented and said, flat tets and massless vertices said, no mass refused",
          "[world][extremes]") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tcbench_degenerate_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // Tet 1 is inverted, tet 3 is flat (its fourth vertex in the plane of the
  // other three, used by no other tet: a vertex without mass).
  write_file_atomically(dir / "odd.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n6\n0 0 0 0\n1 0 0 0\n"
                                          "0 1 0 0\n0 0 1 0\n1 1 1 0\n2 0 0 0\nTetrahedra\n3\n1 3 2 4 0\n"
                                          "2 3 4 5 0\n1 2 6 3 0\nEnd\n");
  write_file_atomically(dir / "flat.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n"
                                           "0 1 0 0\n1 1 0 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n");
  const auto desc_of = [&](const std::string& mesh, double scale, bool passive) {
    WorldDesc desc;
    ObjectDesc o;
    o.name = "thing";
    o.mesh = mesh;
    o.base_dir = dir;
    o.scale = scale;
    o.passive = passive;
    desc.objects.push_back(o);
    return desc;
  };
  const World odd = build_world(desc_of("odd.mesh", 1.0, false));
  REQUIRE(odd.build_warnings.size() == 3);
  CHECK_THAT(odd.build_warnings[0], Catch::Matchers::Contains("1 of 3 tets were given inverted"));
  CHECK_THAT(odd.build_warnings[1], Catch::Matchers::Contains("1 of 3 tets are exactly flat"));
  CHECK_THAT(odd.build_warnings[2], Catch::Matchers::Contains("1 of 6 vertices have no mass"));
  CHECK(build_world(desc_of("box:size=1x1x1,cells=2x2x2", 1.0, false)).build_warnings.empty());
  CHECK_THROWS_WITH(build_world(desc_of("flat.mesh", 1.0, false)), Catch::Matchers::Contains("no mass to simulate"));
  CHECK_THROWS_WITH(build_world(desc_of("box:size=1x1x1,cells=2x2x2", 1e-150, false)),
                    Catch::Matchers::Contains("scale 1e-150"));
  CHECK_NOTHROW(build_world(desc_of("flat.mesh", 1.0, true)));  // a passive obstacle needs no mass
  std::filesystem::remove_all(dir);
}

TEST_CASE("mesh_order curve renumbers meshes at load, stacked copies share the numbering, a latent family keeps "
          "its own",
          "[world][curve]") {
  const auto desc_of = [](MeshOrder order) {
    WorldDesc desc;
    desc.mesh_order = order;
    ObjectDesc box;
    box.name = "box";
    box.mesh = "box:size=0.2x0.1x0.3,cells=4x2x5";
    box.position_m = Vec3(0.01, 0.02, 0.03);
    box.stack.count = 2;
    box.stack.gap_m = 0.01;
    desc.objects.push_back(box);
    ObjectDesc finger;
    finger.name = "finger";
    finger.mesh = "finger:finger_small";
    finger.passive = true;
    finger.position_m = Vec3(0.0, 1.0, 0.0);
    desc.objects.push_back(finger);
    return desc;
  };
  const World file = build_world(desc_of(MeshOrder::File));
  const World curve = build_world(desc_of(MeshOrder::Curve));
  REQUIRE(curve.bodies.size() == 3);
  const TetMesh& mesh = *curve.bodies[0].mesh;
  CHECK(curve.bodies[1].mesh == curve.bodies[0].mesh);  // the stack's copies: one mesh, one numbering
  REQUIRE(mesh.file_vertex_id.size() == mesh.vertex_count());
  bool moved = false;
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(mesh.vertex_count()); ++v) moved |= file_vertex(mesh, v) != v;
  CHECK(moved);  // the generator's lattice order is not the curve's
  CHECK(file.bodies[0].mesh->file_vertex_id.empty());
  for (std::size_t b = 0; b < 2; ++b)  // each vertex built where the file's numbering builds it, with its mass
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(mesh.vertex_count()); ++v) {
      const auto f = static_cast<std::size_t>(file_vertex(mesh, v));
      REQUIRE(curve.bodies[b].x_m[static_cast<std::size_t>(v)] == file.bodies[b].x_m[f]);
      REQUIRE(curve.bodies[b].mass_kg[static_cast<std::size_t>(v)] == Approx(file.bodies[b].mass_kg[f]).epsilon(1e-12));
    }
  CHECK(curve.bodies[2].mesh->file_vertex_id.empty());  // its skinning is defined in its own numbering
  CHECK(curve.bodies[2].x_m == file.bodies[2].x_m);
}
