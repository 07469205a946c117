#include "baselines/fcl_tets_handler.hpp"

#include <ccd/ccd.h>
#include <ccd/vec3.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <map>

#include "method/detection/collision_pairs.hpp"
#include "method/response/penalty_response.hpp"

namespace tcb {
namespace {

// The four faces of a tet in FCL's Convex layout: (count, indices) per face,
// each wound outward for a positively oriented tet (FCL only uses them to
// validate the topology; the broad phase needs the vertices' box).
const std::vector<int> kTetFaces = {3, 0, 2, 1, 3, 0, 1, 3, 3, 1, 2, 3, 3, 0, 3, 2};

// libccd's view of a tet: its four corners, and their mean as its centre.
struct CcdTet {
  std::array<Vec3, 4> corner;
};

void support(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto& tet = *static_cast<const CcdTet*>(object);
  const Vec3 d(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir));
  int best = 0;
  for (int k = 1; k < 4; ++k)
    if (tet.corner[k].dot(d) > tet.corner[best].dot(d)) best = k;
  ccdVec3Set(out, tet.corner[best].x(), tet.corner[best].y(), tet.corner[best].z());
}

void centre(const void* object, ccd_vec3_t* out) {
  const auto& tet = *static_cast<const CcdTet*>(object);
  const Vec3 c = 0.25 * (tet.corner[0] + tet.corner[1] + tet.corner[2] + tet.corner[3]);
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

bool share_vertex(const Tet& a, const Tet& b) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

}  // namespace

struct FclTetsHandler::Impl {
  struct Entry {
    std::int32_t body = -1, tet = -1;
    std::shared_ptr<std::vector<fcl::Vector3d>> corners;
    std::shared_ptr<fcl::Convexd> convex;
    std::unique_ptr<fcl::CollisionObjectd> object;
  };
  // A tet pair found penetrating: moving tet b by depth along direction separates them.
  struct PairContact {
    std::size_t a, b;  // entries
    double depth_m;
    Vec3 direction, point_m;
  };

  CollisionSettings settings;
  std::unique_ptr<CollisionPairs> pairs;
  std::vector<Entry> entries;
  std::vector<char> refit;  // per body: its tets move (not passive and fixed)
  fcl::DynamicAABBTreeCollisionManagerd manager;
  ccd_t ccd{};
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  std::vector<Contact> reported;
  std::int64_t steps = 0;

  static bool collect(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
    auto& out = *static_cast<std::vector<std::pair<std::size_t, std::size_t>>*>(data);
    const auto i = reinterpret_cast<std::size_t>(o1->getUserData());
    const auto j = reinterpret_cast<std::size_t>(o2->getUserData());
    out.emplace_back(std::min(i, j), std::max(i, j));
    return false;  // keep going: every overlapping pair
  }

  CcdTet corners_of(const World& world, const Entry& e) const {
    const Body& body = world.bodies[e.body];
    const Tet& t = body.mesh->tets[e.tet];
    return {{body.x_m[t[0]], body.x_m[t[1]], body.x_m[t[2]], body.x_m[t[3]]}};
  }

  bool may_collide(const World& world, const Entry& a, const Entry& b) const {
    if (!pairs->enabled(a.body, b.body)) return false;
    if (a.body != b.body) return true;
    const TetMesh& mesh = *world.bodies[a.body].mesh;
    return !share_vertex(mesh.tets[a.tet], mesh.tets[b.tet]);
  }
};

FclTetsHandler::FclTetsHandler() : m(std::make_unique<Impl>()) {}
FclTetsHandler::~FclTetsHandler() = default;

const std::vector<Contact>& FclTetsHandler::contacts() const { return m->reported; }

void FclTetsHandler::init(const World& world, const CollisionSettings& settings) {
  m->settings = settings;
  m->pairs = std::make_unique<CollisionPairs>(world);
  m->refit.assign(world.bodies.size(), 0);
  std::size_t count = 0;
  std::vector<char> included(world.bodies.size(), 0);
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    for (std::size_t c = 0; c < world.bodies.size(); ++c) included[b] = included[b] || m->pairs->enabled(b, c);
    if (included[b]) count += world.bodies[b].mesh->tet_count();
    m->refit[b] = !world.bodies[b].passive || world.bodies[b].trajectory != nullptr;
  }
  m->entries.clear();
  m->entries.reserve(count);  // user data points at entries by index; no reallocation below
  const auto faces = std::make_shared<const std::vector<int>>(kTetFaces);
  std::vector<fcl::CollisionObjectd*> objects;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    if (!included[b]) continue;
    for (std::size_t t = 0; t < world.bodies[b].mesh->tet_count(); ++t) {
      Impl::Entry e;
      e.body = static_cast<std::int32_t>(b);
      e.tet = static_cast<std::int32_t>(t);
      e.corners = std::make_shared<std::vector<fcl::Vector3d>>(4);
      const CcdTet now = m->corners_of(world, e);
      for (int k = 0; k < 4; ++k) (*e.corners)[k] = now.corner[k];
      e.convex = std::make_shared<fcl::Convexd>(e.corners, 4, faces);
      e.object = std::make_unique<fcl::CollisionObjectd>(e.convex);
      e.object->setUserData(reinterpret_cast<void*>(m->entries.size()));
      objects.push_back(e.object.get());
      m->entries.push_back(std::move(e));
    }
  }
  m->manager.clear();
  m->manager.registerObjects(objects);
  m->manager.setup();
  CCD_INIT(&m->ccd);
  m->ccd.support1 = support;
  m->ccd.support2 = support;
  m->ccd.center1 = centre;
  m->ccd.center2 = centre;
  m->ccd.max_iterations = 200;
  m->ccd.epa_tolerance = 1e-6 * settings.mean_edge_m;
  m->ccd.dist_tolerance = 1e-9 * settings.mean_edge_m;
  m->steps = 0;
}

StepReport FclTetsHandler::step(World& world, Budget& budget) {
  StepReport report;
  ++m->steps;
  report.cycle = m->steps;

  // Refit the tree to the current positions: one task.
  std::uint64_t refitted = 0;
  for (Impl::Entry& e : m->entries) {
    if (!m->refit[e.body]) continue;
    const CcdTet now = m->corners_of(world, e);
    for (int k = 0; k < 4; ++k) (*e.corners)[k] = now.corner[k];
    e.convex->computeLocalAABB();
    e.object->computeAABB();
    ++refitted;
  }
  if (refitted > 0) m->manager.update();
  budget.charge(refitted);
  report.work_units += refitted;

  // Broad phase: tet pairs whose boxes overlap, of bodies that may collide, in a fixed order.
  m->candidates.clear();
  m->manager.collide(&m->candidates, &Impl::collect);
  std::erase_if(m->candidates, [&](const auto& p) {
    return !m->may_collide(world, m->entries[p.first], m->entries[p.second]);
  });
  std::sort(m->candidates.begin(), m->candidates.end());

  // Narrow phase until the budget is spent: GJK + EPA per pair.
  std::vector<Impl::PairContact> found;
  std::size_t done = 0;
  for (const auto& [i, j] : m->candidates) {
    if (budget.expired()) break;
    budget.charge(1);
    ++report.work_units;
    ++done;
    const CcdTet a = m->corners_of(world, m->entries[i]), b = m->corners_of(world, m->entries[j]);
    ccd_real_t depth = 0.0;
    ccd_vec3_t dir, pos;
    // EPA's depth is good to its tolerance: shallower is touching (exactly
    // face on face it comes out as 1e-17 m), not penetrating.
    if (ccdGJKPenetration(&a, &b, &m->ccd, &depth, &dir, &pos) != 0 || !(depth > m->ccd.epa_tolerance)) continue;
    const Vec3 n(ccdVec3X(&dir), ccdVec3Y(&dir), ccdVec3Z(&dir));
    if (!(n.norm() > 0.0)) continue;
    found.push_back({i, j, depth, n.normalized(), Vec3(ccdVec3X(&pos), ccdVec3Y(&pos), ccdVec3Z(&pos))});
  }
  report.cycle_done = done == m->candidates.size();

  // Response: each pair's force over tet a's vertices (reactions on tet b).
  // Reported: the vertices of both tets, the deepest pair's depth each.
  std::map<std::pair<std::int32_t, std::int32_t>, Contact> reported, forced;
  for (const Impl::PairContact& p : found) {
    const Impl::Entry& ea = m->entries[p.a];
    const Impl::Entry& eb = m->entries[p.b];
    const Body& A = world.bodies[ea.body];
    const Body& B = world.bodies[eb.body];
    const Tet& ta = A.mesh->tets[ea.tet];
    const Tet& tb = B.mesh->tets[eb.tet];
    const auto wa = barycentric_weights(p.point_m, A.x_m[ta[0]], A.x_m[ta[1]], A.x_m[ta[2]], A.x_m[ta[3]]);
    const auto wb = barycentric_weights(p.point_m, B.x_m[tb[0]], B.x_m[tb[1]], B.x_m[tb[2]], B.x_m[tb[3]]);
    const ResponseParams& params = m->settings.response(ea.body, eb.body);
    for (int side = 0; side < 2; ++side) {
      const Impl::Entry& own = side == 0 ? ea : eb;
      const Impl::Entry& other = side == 0 ? eb : ea;
      const Tet& own_tet = side == 0 ? ta : tb;
      for (int k = 0; k < 4; ++k) {
        Contact c;
        c.object = own.body;
        c.vertex = own_tet[k];
        c.other = other.body;
        c.tet = other.tet;
        c.barycentric = side == 0 ? wb : wa;
        c.depth_source = DepthSource::TetPair;
        c.detected_step = c.depth_step = world.step_index;
        c.depth_m = p.depth_m;
        c.direction = side == 0 ? Vec3(-p.direction) : p.direction;  // pushes the vertex out of the other tet
        Contact& seen = reported[{c.object, c.vertex}];
        if (seen.object < 0 || c.depth_m > seen.depth_m) seen = c;
        if (side != 0 || !(wa[k] > 0.0)) continue;
        ResponseParams share = params;
        share.stiffness_n_per_m *= wa[k];
        share.damping_n_s_per_m *= wa[k];
        if (m->settings.response_mode == ResponseMode::Implicit) {
          add_contact_link(world, c, share, m->settings.dt_s);
        } else {
          c.force_n = penalty_force(world, c, share, m->settings.dt_s);
          apply_contact_force(world, c, c.force_n);
        }
        forced.emplace(std::make_pair(c.object, c.vertex), c);
      }
    }
  }
  m->reported.clear();
  for (auto& [key, c] : reported) m->reported.push_back(c);
  for (const auto& [key, c] : forced) {
    report.exact_points.emplace_back(c.object, c.vertex);
    report.force_points.push_back({c.object, c.vertex, ForceSource::Computed});
  }
  report.colliding_points = static_cast<std::int64_t>(m->reported.size());
  report.exact_forces = static_cast<std::int64_t>(forced.size());
  return report;
}

}  // namespace tcb
