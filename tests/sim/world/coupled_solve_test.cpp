// Implicit penalty contact (sim/world/coupled_solve.hpp): links solved with
// the bodies dissipate where explicit forces explode, conserve momentum,
// apply exactly the force their solve used, and never pull.
#include "sim/world/coupled_solve.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "sim/world/world.hpp"
#include "sim/world/world_desc.hpp"

using namespace tcb;

namespace {

ObjectDesc box(const std::string& name, const Vec3& position, bool passive, Material material = {}) {
  ObjectDesc o;
  o.name = name;
  o.mesh = "box:size=0.1x0.1x0.1,cells=1x1x1";
  o.position_m = position;
  o.passive = passive;
  o.material = material;
  return o;
}

WorldDesc no_gravity(std::vector<ObjectDesc> objects) {
  WorldDesc d;
  d.gravity_m_per_s2 = Vec3::Zero();
  d.objects = std::move(objects);
  return d;
}

// The lowest vertex of a body (its contact point in these tests).
std::int32_t lowest_vertex(const Body& b) {
  return static_cast<std::int32_t>(
      std::min_element(b.x_m.begin(), b.x_m.end(), [](const Vec3& a, const Vec3& c) { return a.y() < c.y(); }) -
      b.x_m.begin());
}

ContactLink link_into(const World& world, std::int32_t point_body, std::int32_t vertex, std::int32_t tet_body,
                      double depth_m, double k, double c) {
  ContactLink l;
  l.point_body = point_body;
  l.vertex = vertex;
  l.tet_body = tet_body;
  l.tet_vertices = world.bodies[tet_body].mesh->tets[0];
  l.weights = {0.25, 0.25, 0.25, 0.25};
  l.normal = Vec3(0.0, 1.0, 0.0);
  l.depth_m = depth_m;
  l.stiffness_n_per_m = k;
  l.damping_n_s_per_m = c;
  return l;
}

Vec3 momentum(const World& world) {
  Vec3 p = Vec3::Zero();
  for (const Body& b : world.bodies)
    if (!b.passive)
      for (std::size_t i = 0; i < b.x_m.size(); ++i) p += b.mass_kg[i] * b.v_m_per_s[i];
  return p;
}

}  // namespace

TEST_CASE("a link 100x stiffer than the explicit bound: implicit never gains energy, explicit explodes", "[contact]") {
  for (const bool implicit : {true, false}) {
    INFO((implicit ? "implicit" : "explicit"));
    World world = build_world(no_gravity({box("floor", Vec3::Zero(), true), box("cube", Vec3(0, 0.1, 0), false)}));
    Body& cube = world.bodies[1];
    const std::int32_t v = lowest_vertex(cube);
    const double dt = 1e-3, m = cube.mass_kg[v];
    const double k = 100.0 * 4.0 * m / (dt * dt);
    const double y0 = cube.x_m[v].y(), d0 = 1e-3;  // the vertex starts 1 mm inside
    const auto depth = [&] { return d0 - (cube.x_m[v].y() - y0); };
    const auto energy = [&] {
      const double d = std::max(0.0, depth());
      return world.kinetic_energy_j() + world.elastic_energy_j() + 0.5 * k * d * d;
    };
    double e = energy(), largest = e;
    const double e0 = e;
    bool grew = false;
    for (int s = 0; s < 300 && std::isfinite(e); ++s) {
      if (depth() > 0.0) {
        if (implicit) world.contact_links.push_back(link_into(world, 1, v, 0, depth(), k, 0.0));
        else cube.contact_force_n[v] += k * depth() * Vec3(0, 1, 0);
      }
      world.step(dt);
      const double next = energy();
      grew = grew || next > e * (1.0 + 1e-9) + 1e-15;
      e = next;
      largest = std::max(largest, e);
    }
    if (implicit) {
      CHECK_FALSE(grew);
      CHECK(e <= e0);
    } else {
      CHECK((!std::isfinite(e) || largest > 100.0 * e0));
    }
  }
}

TEST_CASE("two free cubes joined by links conserve momentum to 1e-12", "[contact]") {
  Material tight;
  tight.cg_tolerance = 1e-14;
  tight.cg_max_iterations = 2000;
  World world = build_world(no_gravity({box("a", Vec3::Zero(), false, tight), box("b", Vec3(0, 0.099, 0), false, tight)}));
  for (std::size_t i = 0; i < world.bodies[0].v_m_per_s.size(); ++i) world.bodies[0].v_m_per_s[i] = Vec3(0.3, 0.5, -0.2);
  for (std::size_t i = 0; i < world.bodies[1].v_m_per_s.size(); ++i) world.bodies[1].v_m_per_s[i] = Vec3(-0.1, -0.7, 0.4);
  const Vec3 p0 = momentum(world);
  const Body& b = world.bodies[1];
  std::int64_t links = 0;
  for (int s = 0; s < 20; ++s) {
    const std::int32_t v = lowest_vertex(b);
    world.contact_links.push_back(link_into(world, 1, v, 0, 1e-3, 5e3, 2.0));
    world.step(1e-3);
    links += world.last_contact_solve.links - world.last_contact_solve.dropped;
  }
  CHECK(links > 0);  // the links really acted
  CHECK((momentum(world) - p0).norm() <= 1e-12 * p0.norm());
}

TEST_CASE("the contact Jacobian: finite differences of the geometric force match h (h k + c) J^T n n^T J", "[contact]") {
  // The force on the point at the end of the step, from the positions the new
  // velocities give (depth carried geometrically) and the damper.
  const double h = 1e-3, k = 3e4, c = 7.0, d = 2e-3;
  const std::array<double, 4> w = {0.1, 0.2, 0.3, 0.4};
  const Vec3 n = Vec3(1.0, 2.0, 2.0).normalized();
  const auto force = [&](const Eigen::Matrix<double, 15, 1>& vel) {  // [v_point, v_tet0..3]
    Vec3 g = vel.segment<3>(0);
    for (int q = 0; q < 4; ++q) g -= w[q] * vel.segment<3>(3 + 3 * q);
    const double s = n.dot(g);
    const double depth = d - n.dot(h * g);  // the point moves h g relative to the tet
    const double lambda = k * depth - c * s;
    Eigen::Matrix<double, 15, 1> f;
    f.segment<3>(0) = lambda * n;
    for (int q = 0; q < 4; ++q) f.segment<3>(3 + 3 * q) = -w[q] * lambda * n;
    return f;
  };
  Eigen::Matrix<double, 3, 15> jacobian = Eigen::Matrix<double, 3, 15>::Zero();  // J: g = J v
  jacobian.block<3, 3>(0, 0).setIdentity();
  for (int q = 0; q < 4; ++q) jacobian.block<3, 3>(0, 3 + 3 * q) = -w[q] * Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 15, 15> analytic = -(h * k + c) * jacobian.transpose() * n * n.transpose() * jacobian;
  Eigen::Matrix<double, 15, 1> v0;
  for (int i = 0; i < 15; ++i) v0[i] = 0.1 * std::sin(1.0 + i);
  Eigen::Matrix<double, 15, 15> numeric;
  const double eps = 1e-6;
  for (int j = 0; j < 15; ++j) {
    Eigen::Matrix<double, 15, 1> up = v0, down = v0;
    up[j] += eps;
    down[j] -= eps;
    numeric.col(j) = (force(up) - force(down)) / (2.0 * eps);
  }
  CHECK((numeric - analytic).norm() <= 1e-6 * analytic.norm());
  // The link's lambda is that force's magnitude.
  ContactLink l;
  l.depth_m = d;
  l.stiffness_n_per_m = k;
  l.damping_n_s_per_m = c;
  Vec3 g = v0.segment<3>(0);
  for (int q = 0; q < 4; ++q) g -= w[q] * v0.segment<3>(3 + 3 * q);
  CHECK(link_lambda(l, n.dot(g), h) == Approx(force(v0).segment<3>(0).dot(n)).epsilon(1e-12));
}

TEST_CASE("the solve applies exactly the force it solved with (mass-spring: m (v+ - v) = h (f + f_contact))",
          "[contact]") {
  Material springs;
  springs.model = MaterialModel::MassSpring;
  springs.integrator = Integrator::EulerCromer;
  springs.damping_mass_per_s = 0.0;
  springs.cg_tolerance = 1e-14;
  World world = build_world(no_gravity({box("floor", Vec3::Zero(), true), box("cube", Vec3(0, 0.099, 0), false, springs)}));
  Body& cube = world.bodies[1];
  const std::int32_t v = lowest_vertex(cube);
  cube.v_m_per_s[v] = Vec3(0.0, -0.3, 0.1);
  const std::vector<Vec3> v_before = cube.v_m_per_s;
  std::vector<Vec3> f_spring(cube.x_m.size());
  cube.model->elastic_forces(cube.x_m, f_spring);
  world.contact_links.push_back(link_into(world, 1, v, 0, 1e-3, 2e3, 1.0));
  const double h = 1e-3;
  world.step(h);
  REQUIRE(world.last_contact_solve.links == 1);
  REQUIRE(world.last_contact_solve.dropped == 0);
  CHECK(cube.applied_contact_force_n[v].y() > 0.0);
  for (std::size_t i = 0; i < cube.x_m.size(); ++i) {
    const Vec3 lhs = cube.mass_kg[i] * (cube.v_m_per_s[i] - v_before[i]);
    const Vec3 rhs = h * (f_spring[i] + cube.applied_contact_force_n[i]);
    CHECK((lhs - rhs).norm() <= 1e-9 * (rhs.norm() + 1e-12));
  }
}

TEST_CASE("cubes separating at 1 m/s: the unilateral check drops the link, no pulling force", "[contact]") {
  World world = build_world(no_gravity({box("a", Vec3::Zero(), false), box("b", Vec3(0, 0.0999, 0), false)}));
  for (Vec3& v : world.bodies[1].v_m_per_s) v = Vec3(0.0, 0.5, 0.0);
  for (Vec3& v : world.bodies[0].v_m_per_s) v = Vec3(0.0, -0.5, 0.0);
  const std::int32_t v = lowest_vertex(world.bodies[1]);
  world.contact_links.push_back(link_into(world, 1, v, 0, 1e-4, 1e3, 5.0));
  world.step(1e-3);
  const ContactSolveStats& s = world.last_contact_solve;
  CHECK(s.dropped == 1);
  CHECK(s.resolved == 1);
  CHECK(s.still_pulling == 0);
  for (const Body& b : world.bodies)
    for (const Vec3& f : b.applied_contact_force_n) CHECK(f == Vec3::Zero());
}
