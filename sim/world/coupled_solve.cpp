#include "sim/world/coupled_solve.hpp"

#include <array>
#include <numeric>
#include <stdexcept>

#include "sim/world/world.hpp"

namespace tcb {
namespace {

// One component: its bodies' unknown velocities stacked, and its links.
class Component {
 public:
  Component(World& world, std::vector<std::int32_t> bodies, std::vector<const ContactLink*> links, double dt)
      : m_world(world), m_bodies(std::move(bodies)), m_links(std::move(links)), m_dt(dt) {
    m_offset.assign(world.bodies.size(), -1);
    std::size_t size = 0;
    for (const std::int32_t b : m_bodies) {
      m_offset[b] = static_cast<std::ptrdiff_t>(size);
      size += 3 * world.bodies[b].x_m.size();
    }
    m_size = size;
    // Each link's unknowns, looked up once: the CG's products read them every
    // iteration.
    m_unknowns.reserve(m_links.size());
    for (const ContactLink* link : m_links) {
      LinkUnknowns u;
      u.point = unknown(link->point_body, link->vertex);
      for (int k = 0; k < 4; ++k) u.tet[k] = unknown(link->tet_body, link->tet_vertices[k]);
      m_unknowns.push_back(u);
    }
  }

  ContactSolveStats solve() {
    ContactSolveStats stats;
    stats.components = 1;
    m_rhs.resize(static_cast<Eigen::Index>(m_size));
    m_diagonal.resize(static_cast<Eigen::Index>(m_size));
    Eigen::VectorXd v(static_cast<Eigen::Index>(m_size));
    double tolerance = 1.0;
    int max_iterations = 0;
    for (const std::int32_t b : m_bodies) {
      Body& body = m_world.bodies[b];
      if (!body.model->begin_linear_step(body.x_m, body.v_m_per_s, body.external_force_n, m_dt))
        throw std::logic_error("body '" + body.name + "' has no linear step for implicit contact");
      const auto n = static_cast<Eigen::Index>(3 * body.x_m.size());
      m_rhs.segment(m_offset[b], n) = body.model->rhs();
      m_diagonal.segment(m_offset[b], n) = body.model->diagonal();
      for (std::size_t i = 0; i < body.x_m.size(); ++i)
        v.segment<3>(m_offset[b] + 3 * static_cast<Eigen::Index>(i)) = body.mass_kg[i] > 0.0 ? body.v_m_per_s[i] : Vec3(Vec3::Zero());
      tolerance = std::min(tolerance, body.model->solver_tolerance());
      max_iterations = std::max(max_iterations, body.model->solver_max_iterations());
    }
    m_active.assign(m_links.size(), 1);
    std::vector<double> lambda;
    int iterations = 0;
    bool converged = conjugate_gradients(v, tolerance, max_iterations, iterations);
    stats.iterations += iterations;
    const int first_iterations = iterations;
    lambda = forces(v);
    std::int64_t pulling = 0;
    for (std::size_t l = 0; l < m_links.size(); ++l)
      if (lambda[l] < 0.0) m_active[l] = 0, ++pulling;
    if (pulling > 0) {  // unilateral: drop the links that pull and solve once more
      stats.resolved = 1;
      stats.dropped = pulling;
      const bool first_converged = converged;
      converged = conjugate_gradients(v, tolerance, max_iterations, iterations) && first_converged;
      stats.iterations += iterations;
      iterations += first_iterations;
      lambda = forces(v);
      for (std::size_t l = 0; l < m_links.size(); ++l) stats.still_pulling += m_active[l] && lambda[l] < 0.0;
    }
    stats.converged = converged;
    // The forces the kept links applied, and the bodies' new state.
    for (std::size_t l = 0; l < m_links.size(); ++l) {
      if (!m_active[l]) continue;
      const ContactLink& link = *m_links[l];
      const Vec3 f = lambda[l] * link.normal;
      m_world.bodies[link.point_body].applied_contact_force_n[link.vertex] += f;
      for (int k = 0; k < 4; ++k)
        m_world.bodies[link.tet_body].applied_contact_force_n[link.tet_vertices[k]] -= link.weights[k] * f;
    }
    // The component's CG iterations (both solves) are reported once, on its
    // first body, so a sum over the bodies counts each iteration once.
    for (const std::int32_t b : m_bodies) {
      Body& body = m_world.bodies[b];
      const auto n = static_cast<Eigen::Index>(3 * body.x_m.size());
      body.model->end_linear_step(body.x_m, body.v_m_per_s, v.segment(m_offset[b], n), m_dt,
                                  b == m_bodies.front() ? iterations : 0, converged);
    }
    return stats;
  }

 private:
  // The index of a vertex's first unknown, or -1 when its velocity is known
  // (a passive or driven body, or a massless, pinned vertex).
  std::ptrdiff_t unknown(std::int32_t body, std::int32_t vertex) const {
    if (m_offset[body] < 0 || !(m_world.bodies[body].mass_kg[vertex] > 0.0)) return -1;
    return m_offset[body] + 3 * static_cast<std::ptrdiff_t>(vertex);
  }

  // The velocity of a vertex outside the unknowns over this step: a driven
  // body's motion to its trajectory at t + h, a pinned vertex's zero, a
  // static passive body's (zero) velocity.
  Vec3 known_velocity(std::int32_t body, std::int32_t vertex) const {
    const Body& b = m_world.bodies[body];
    if (m_offset[body] >= 0) return Vec3::Zero();  // a pinned vertex of a body being solved
    if (b.trajectory) return (b.shape_m[vertex] + b.trajectory->at(m_world.time_s + m_dt) - b.x_m[vertex]) / m_dt;
    return b.v_m_per_s[vertex];
  }

  // J v over the unknowns only, for link l.
  Vec3 unknown_part(std::size_t l, const Eigen::VectorXd& v) const {
    const ContactLink& link = *m_links[l];
    const LinkUnknowns& u = m_unknowns[l];
    Vec3 g = Vec3::Zero();
    if (u.point >= 0) g += v.segment<3>(u.point);
    for (int k = 0; k < 4; ++k)
      if (u.tet[k] >= 0) g -= link.weights[k] * v.segment<3>(u.tet[k]);
    return g;
  }

  // The part of link l's relative velocity that is known over this step.
  Vec3 known_part(std::size_t l) const {
    const ContactLink& link = *m_links[l];
    const LinkUnknowns& u = m_unknowns[l];
    Vec3 g = Vec3::Zero();
    if (u.point < 0) g += known_velocity(link.point_body, link.vertex);
    for (int k = 0; k < 4; ++k)
      if (u.tet[k] < 0) g -= link.weights[k] * known_velocity(link.tet_body, link.tet_vertices[k]);
    return g;
  }

  // out += J^T f over the unknowns, for link l.
  void add_transposed(std::size_t l, const Vec3& f, Eigen::VectorXd& out) const {
    const ContactLink& link = *m_links[l];
    const LinkUnknowns& u = m_unknowns[l];
    if (u.point >= 0) out.segment<3>(u.point) += f;
    for (int k = 0; k < 4; ++k)
      if (u.tet[k] >= 0) out.segment<3>(u.tet[k]) -= link.weights[k] * f;
  }

  double coupling(const ContactLink& link) const {
    return m_dt * (m_dt * link.stiffness_n_per_m + link.damping_n_s_per_m);
  }

  void multiply(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
    out.resize(v.size());
    for (const std::int32_t b : m_bodies) {
      const auto n = static_cast<Eigen::Index>(3 * m_world.bodies[b].x_m.size());
      m_world.bodies[b].model->multiply(v.segment(m_offset[b], n), out.segment(m_offset[b], n));
    }
    for (std::size_t l = 0; l < m_links.size(); ++l) {
      if (!m_active[l]) continue;
      const ContactLink& link = *m_links[l];
      const double s = link.normal.dot(unknown_part(l, v));
      add_transposed(l, coupling(link) * s * link.normal, out);
    }
  }

  // Right-hand side and Jacobi diagonal with the active links' terms.
  void link_terms(Eigen::VectorXd& rhs, Eigen::VectorXd& diagonal) const {
    rhs = m_rhs;
    diagonal = m_diagonal;
    for (std::size_t l = 0; l < m_links.size(); ++l) {
      if (!m_active[l]) continue;
      const ContactLink& link = *m_links[l];
      const double a = coupling(link);
      const Vec3 u = known_part(l);
      add_transposed(l, (m_dt * link.stiffness_n_per_m * link.depth_m - a * link.normal.dot(u)) * link.normal, rhs);
      const Vec3 nn = link.normal.cwiseProduct(link.normal);
      const LinkUnknowns& unknowns = m_unknowns[l];
      if (unknowns.point >= 0) diagonal.segment<3>(unknowns.point) += a * nn;
      for (int k = 0; k < 4; ++k)
        if (unknowns.tet[k] >= 0) diagonal.segment<3>(unknowns.tet[k]) += a * link.weights[k] * link.weights[k] * nn;
    }
  }

  // Jacobi-preconditioned CG from the guess in v; true when |r| <= tol |b|.
  bool conjugate_gradients(Eigen::VectorXd& v, double tolerance, int max_iterations, int& iterations) {
    Eigen::VectorXd rhs, diagonal;
    link_terms(rhs, diagonal);
    const Eigen::VectorXd inverse = diagonal.cwiseInverse();
    const double threshold = tolerance * rhs.norm();
    Eigen::VectorXd r, ap;
    multiply(v, ap);
    r = rhs - ap;
    Eigen::VectorXd z = inverse.cwiseProduct(r), p = z;
    double rz = r.dot(z);
    iterations = 0;
    while (r.norm() > threshold) {
      if (iterations == max_iterations) return false;
      multiply(p, ap);
      const double alpha = rz / p.dot(ap);
      v += alpha * p;
      r -= alpha * ap;
      z = inverse.cwiseProduct(r);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
      ++iterations;
    }
    return true;
  }

  // lambda of every link with the velocities v (0 for inactive links).
  std::vector<double> forces(const Eigen::VectorXd& v) const {
    std::vector<double> lambda(m_links.size(), 0.0);
    for (std::size_t l = 0; l < m_links.size(); ++l) {
      if (!m_active[l]) continue;
      const ContactLink& link = *m_links[l];
      const double s = link.normal.dot(unknown_part(l, v) + known_part(l));
      lambda[l] = link_lambda(link, s, m_dt);
    }
    return lambda;
  }

  World& m_world;
  std::vector<std::int32_t> m_bodies;
  std::vector<const ContactLink*> m_links;
  // A link's unknowns (unknown()): its point's, its tet's four vertices'.
  struct LinkUnknowns {
    std::ptrdiff_t point;
    std::array<std::ptrdiff_t, 4> tet;
  };
  std::vector<LinkUnknowns> m_unknowns;
  double m_dt;
  std::vector<std::ptrdiff_t> m_offset;  // per body: first unknown, -1 when not in the component
  std::size_t m_size = 0;
  Eigen::VectorXd m_rhs, m_diagonal;
  std::vector<char> m_active;
};

// Union-find root of a body.
std::int32_t root(std::vector<std::int32_t>& parent, std::int32_t b) {
  while (parent[b] != b) b = parent[b] = parent[parent[b]];
  return b;
}

}  // namespace

ContactSolveStats step_linked_bodies(World& world, std::span<const ContactLink> links, double dt_s,
                                     std::vector<char>& integrated) {
  const auto count = static_cast<std::int32_t>(world.bodies.size());
  const auto dynamic = [&](std::int32_t b) { return !world.bodies[b].passive && world.bodies[b].model; };
  std::vector<std::int32_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> linked(count, 0);
  for (const ContactLink& l : links) {
    const bool a = dynamic(l.point_body), b = dynamic(l.tet_body);
    if (a) linked[l.point_body] = 1;
    if (b) linked[l.tet_body] = 1;
    if (a && b) parent[root(parent, l.point_body)] = root(parent, l.tet_body);
  }
  ContactSolveStats stats;
  stats.links = static_cast<std::int64_t>(links.size());
  for (std::int32_t r = 0; r < count; ++r) {
    if (!linked[r] || root(parent, r) != r) continue;
    std::vector<std::int32_t> bodies;
    for (std::int32_t b = 0; b < count; ++b)
      if (linked[b] && root(parent, b) == r) bodies.push_back(b);
    std::vector<const ContactLink*> mine;
    for (const ContactLink& l : links) {
      const std::int32_t side = dynamic(l.point_body) ? l.point_body : l.tet_body;
      if (dynamic(side) && root(parent, side) == r) mine.push_back(&l);
    }
    const ContactSolveStats s = Component(world, bodies, std::move(mine), dt_s).solve();
    stats.components += s.components;
    stats.resolved += s.resolved;
    stats.dropped += s.dropped;
    stats.still_pulling += s.still_pulling;
    stats.iterations += s.iterations;
    stats.converged = stats.converged && s.converged;
    for (const std::int32_t b : bodies) integrated[b] = 1;
  }
  return stats;
}

}  // namespace tcb
