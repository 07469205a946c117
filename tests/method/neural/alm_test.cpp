// The augmented Lagrangian resolution (method/neural/alm.hpp) on constraints
// whose projections are known in closed form, and cut by work budgets.
#include "method/neural/alm.hpp"

#include <catch2/catch.hpp>

using namespace tcb;
using namespace tcb::neural;

namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd z(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double x : v) z[i++] = x;
  return z;
}

AlmState solve(const Eigen::VectorXd& z0, const Constraint& c, const AlmSettings& s = {}) {
  AlmState state = alm_start(z0, s);
  Budget budget = Budget::unlimited();
  REQUIRE(alm_resume(state, c, s, budget));
  return state;
}

}  // namespace

TEST_CASE("ALM: a half-space constraint lands on the orthogonal projection", "[neural][alm]") {
  const Eigen::VectorXd a = vec({1.0, -2.0, 0.5, 3.0});
  const double b = 0.7;
  const Constraint c = [&](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    g = a;
    return a.dot(z) - b;
  };
  for (const Eigen::VectorXd& z0 : {vec({1.0, 0.0, 0.0, 1.0}), vec({0.3, -0.9, 0.2, 0.4}), vec({5.0, -5.0, 5.0, 5.0})}) {
    REQUIRE(a.dot(z0) > b);
    const Eigen::VectorXd expected = z0 - (a.dot(z0) - b) / a.squaredNorm() * a;
    const AlmState s = solve(z0, c);
    CHECK(s.converged);
    CHECK((s.z - expected).norm() < 1e-6 * (1.0 + expected.norm()));
    CHECK(s.c <= AlmSettings{}.feasibility_tolerance);
  }
}

TEST_CASE("ALM: the outside of a ball: a point inside goes radially to the sphere", "[neural][alm]") {
  const Constraint c = [](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    g = -2.0 * z;
    return 1.0 - z.squaredNorm();
  };
  const Eigen::VectorXd z0 = vec({0.3, 0.1, -0.2});
  const AlmState s = solve(z0, c);
  CHECK(s.converged);
  CHECK((s.z - z0.normalized()).norm() < 1e-6);
}

TEST_CASE("ALM: a feasible start stays where it is", "[neural][alm]") {
  const Constraint c = [](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    g = Eigen::VectorXd::Ones(z.size());
    return z.sum() - 10.0;
  };
  const Eigen::VectorXd z0 = vec({0.1, 0.2});
  const AlmState s = solve(z0, c);
  CHECK(s.converged);
  CHECK(s.z == z0);
  CHECK(s.evaluations == 1);
}

TEST_CASE("ALM: with no feasible code it gives up after max_outer, not converged", "[neural][alm]") {
  const Constraint c = [](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    g = Eigen::VectorXd::Zero(z.size());
    return 1.0;
  };
  AlmSettings settings;
  settings.max_outer = 5;
  const AlmState s = solve(vec({0.5, 0.5}), c, settings);
  CHECK_FALSE(s.converged);
  CHECK(s.outer == 5);
  CHECK(s.z == vec({0.5, 0.5}));
}

TEST_CASE("ALM: stopped by work budgets and resumed, it ends bit-identical to one run", "[neural][alm]") {
  const Constraint c = [](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
    // A curved boundary: z1 >= z0^2 + 0.5 (feasible above the parabola).
    g = vec({2.0 * z[0], -1.0});
    return z[0] * z[0] + 0.5 - z[1];
  };
  const Eigen::VectorXd z0 = vec({0.8, -0.3});
  const AlmSettings settings;
  const AlmState whole = solve(z0, c, settings);
  REQUIRE(whole.converged);
  for (const std::uint64_t units : {1u, 3u, 7u}) {
    AlmState state = alm_start(z0, settings);
    int pieces = 0;
    for (bool done = false; !done; ++pieces) {
      Budget budget = Budget::work_units(units);
      done = alm_resume(state, c, settings, budget);
      CHECK(budget.spent() <= units);
    }
    CHECK(pieces > 1);
    CHECK(state.z == whole.z);
    CHECK(state.evaluations == whole.evaluations);
  }
  // A zero budget does nothing.
  AlmState state = alm_start(z0, settings);
  Budget none = Budget::work_units(0);
  CHECK_FALSE(alm_resume(state, c, settings, none));
  CHECK(state.evaluations == 0);
}
