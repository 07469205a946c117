// Both elastic models: forces are the negative energy gradient, rigid motions
// cost nothing, energy never grows without forcing, squashed and inverted
// elements recover.
#include <catch2/catch.hpp>

#include <random>

#include "sim/dynamics/corotational_fem.hpp"
#include "sim/dynamics/mass_spring.hpp"
#include "sim/mesh/box_mesh.hpp"
#include "tests/sim/dynamics/fixtures.hpp"

using namespace tcb;
using test::perturbed;

namespace {

Material material_for(MaterialModel model, Integrator integrator) {
  Material m;
  m.model = model;
  m.integrator = integrator;
  m.youngs_modulus_pa = 1.0e4;
  m.poisson_ratio = 0.3;
  m.density_kg_per_m3 = 1000.0;
  m.cg_tolerance = 1e-10;
  return m;
}

}  // namespace

TEST_CASE("elastic forces are minus the energy gradient", "[dynamics]") {
  const TetMesh mesh = make_box_mesh(Vec3(1.0, 0.5, 0.8), 2, 1, 2);
  for (MaterialModel model : {MaterialModel::CorotationalFem, MaterialModel::MassSpring}) {
    INFO(to_string(model));
    const auto elastic = make_elastic_model(mesh, mesh.positions_m, material_for(model, Integrator::EulerCromer));
    const std::vector<Vec3> x = perturbed(mesh.positions_m, 0.1, 5);
    std::vector<Vec3> f(x.size());
    elastic->elastic_forces(x, f);
    const double h = 1e-6;
    for (std::size_t i = 0; i < x.size(); i += 3)
      for (int d = 0; d < 3; ++d) {
        std::vector<Vec3> plus = x, minus = x;
        plus[i][d] += h;
        minus[i][d] -= h;
        const double gradient = (elastic->elastic_energy_j(plus) - elastic->elastic_energy_j(minus)) / (2 * h);
        REQUIRE(f[i][d] == Approx(-gradient).margin(1e-4 * f[i].norm() + 1e-6));
      }
  }
}

TEST_CASE("a rigidly moved corotational element has zero elastic force", "[dynamics]") {
  const TetMesh mesh = make_box_mesh(Vec3(0.2, 0.1, 0.3), 2, 2, 2);
  CorotationalFem fem(mesh, mesh.positions_m, material_for(MaterialModel::CorotationalFem, Integrator::ImplicitEuler));
  std::mt19937 rng(2);
  std::normal_distribution<double> n;
  // The same deformation, unrotated, gives the force scale to compare with.
  std::vector<Vec3> f(mesh.vertex_count());
  const std::vector<Vec3> deformed = perturbed(mesh.positions_m, 0.01, 3);
  fem.elastic_forces(deformed, f);
  const double deformation_energy = fem.elastic_energy_j(deformed);
  double scale = 0.0;
  for (const Vec3& v : f) scale = std::max(scale, v.norm());
  REQUIRE(scale > 0.0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const Vec3 t(n(rng), n(rng), n(rng));
    std::vector<Vec3> x = mesh.positions_m;
    for (Vec3& p : x) p = q * p + t;
    fem.elastic_forces(x, f);
    double largest = 0.0;
    for (const Vec3& v : f) largest = std::max(largest, v.norm());
    REQUIRE(largest < 1e-8 * scale);
    INFO("energy " << fem.elastic_energy_j(x) << " J against " << deformation_energy << " J");
    REQUIRE(fem.elastic_energy_j(x) < 1e-9 * deformation_energy);
  }
}

TEST_CASE("energy does not grow without forcing", "[dynamics]") {
  const TetMesh mesh = make_box_mesh(Vec3(0.2, 0.2, 0.2), 3, 3, 3);
  struct Case {
    MaterialModel model;
    Integrator integrator;
    double dt;
  };
  for (const Case c : {Case{MaterialModel::CorotationalFem, Integrator::ImplicitEuler, 1e-2},
                       Case{MaterialModel::CorotationalFem, Integrator::ImplicitEuler, 1e-4},
                       Case{MaterialModel::MassSpring, Integrator::EulerCromer, 1e-4},
                       Case{MaterialModel::MassSpring, Integrator::VelocityVerlet, 1e-4}}) {
    INFO(to_string(c.model) << " " << to_string(c.integrator) << " dt " << c.dt);
    const auto elastic = make_elastic_model(mesh, mesh.positions_m, material_for(c.model, c.integrator));
    std::vector<Vec3> x = perturbed(mesh.positions_m, 0.01, 9);
    std::vector<Vec3> v(x.size(), Vec3::Zero());
    const std::vector<Vec3> no_force(x.size(), Vec3::Zero());
    const auto& m = elastic->vertex_masses_kg();
    const auto energy = [&] {
      double e = elastic->elastic_energy_j(x);
      for (std::size_t i = 0; i < x.size(); ++i) e += 0.5 * m[i] * v[i].squaredNorm();
      return e;
    };
    const double initial = energy();
    REQUIRE(initial > 0.0);
    double largest = initial;
    for (int s = 0; s < 500; ++s) {
      elastic->step(x, v, no_force, c.dt);
      largest = std::max(largest, energy());
    }
    // Implicit Euler dissipates; the symplectic explicit schemes oscillate
    // around the initial energy by O(dt^2).
    const double allowed = c.integrator == Integrator::ImplicitEuler ? 1e-9 : 2e-2;
    CHECK(largest <= initial * (1.0 + allowed));
    CHECK(energy() <= initial * (1.0 + allowed));
  }
}

TEST_CASE("mass-spring volume term restores a squashed and an inverted tet", "[dynamics]") {
  const std::vector<Vec3> rest = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
  const TetMesh mesh = build_tet_mesh(rest, {{0, 1, 2, 3}});
  Material material = material_for(MaterialModel::MassSpring, Integrator::EulerCromer);
  material.damping_mass_per_s = 20.0;
  MassSpring springs(mesh, rest, material);
  const double rest_volume = signed_volume(rest[0], rest[1], rest[2], rest[3]);
  for (double squash : {0.3, -0.5}) {  // -0.5 mirrors vertex 3 through the base: inverted
    INFO("squash " << squash);
    std::vector<Vec3> x = rest;
    x[3].z() *= squash;
    std::vector<Vec3> v(4, Vec3::Zero());
    const std::vector<Vec3> no_force(4, Vec3::Zero());
    // Slowest mode: about 26 rad/s; 3 s at damping 20/s leaves e^-60 of it.
    for (int s = 0; s < 30000; ++s) springs.step(x, v, no_force, 1e-4);
    CHECK(signed_volume(x[0], x[1], x[2], x[3]) == Approx(rest_volume).epsilon(1e-3));
  }
}

TEST_CASE("massless vertices never move", "[dynamics]") {
  std::vector<Vec3> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {5, 5, 5}};
  const TetMesh mesh = build_tet_mesh(rest, {{0, 1, 2, 3}});
  for (MaterialModel model : {MaterialModel::CorotationalFem, MaterialModel::MassSpring}) {
    const auto elastic = make_elastic_model(mesh, rest, material_for(model, Integrator::EulerCromer));
    std::vector<Vec3> x = rest;
    std::vector<Vec3> v(5, Vec3(1, 0, 0));
    const std::vector<Vec3> force(5, Vec3(0, -10, 0));
    elastic->step(x, v, force, 1e-3);
    CHECK(x[4] == rest[4]);
    CHECK(v[4] == Vec3::Zero());
    CHECK(x[0].allFinite());
  }
}
