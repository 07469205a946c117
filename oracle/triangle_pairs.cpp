#include "oracle/triangle_pairs.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <limits>

namespace tcb {

namespace {

using Model = fcl::BVHModel<fcl::AABBd>;

std::vector<fcl::Vector3d> surface_points(const Body& body) {
  std::vector<fcl::Vector3d> points;
  points.reserve(body.x_m.size());
  for (const Vec3& x : body.x_m) points.emplace_back(x.x(), x.y(), x.z());
  return points;  // all vertices, so the triangles keep the mesh's indices
}

}  // namespace

struct SurfaceTrianglePairs::Models {
  // BVHModel has no copy assignment (double free in FCL 0.7): shared_ptr only.
  std::vector<std::shared_ptr<Model>> model;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> object;
};

SurfaceTrianglePairs::SurfaceTrianglePairs(const World& world) : models_(std::make_unique<Models>()) {
  const std::size_t n = world.bodies.size();
  models_->model.resize(n);
  models_->object.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    bool partner = false;
    for (std::size_t j = 0; j < n; ++j) partner |= i != j && !(world.bodies[i].passive && world.bodies[j].passive);
    if (!partner) continue;
    const Body& body = world.bodies[i];
    std::vector<fcl::Triangle> triangles;
    triangles.reserve(body.mesh->surface.size());
    for (const Triangle& f : body.mesh->surface) triangles.emplace_back(f[0], f[1], f[2]);
    auto model = std::make_shared<Model>();
    model->beginModel();
    model->addSubModel(surface_points(body), triangles);
    model->endModel();
    model->computeLocalAABB();
    models_->model[i] = model;
    models_->object[i] = std::make_unique<fcl::CollisionObjectd>(model, fcl::Transform3d::Identity());
  }
}

SurfaceTrianglePairs::~SurfaceTrianglePairs() = default;

std::vector<TrianglePair> SurfaceTrianglePairs::find(const World& world) {
  const std::size_t n = world.bodies.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!models_->model[i]) continue;
    Model& model = *models_->model[i];
    model.beginUpdateModel();
    model.updateSubModel(surface_points(world.bodies[i]));
    model.endUpdateModel(true, true);  // refit, bottom-up
    model.computeLocalAABB();          // FCL does not do these two itself
    models_->object[i]->computeAABB();
  }
  std::vector<TrianglePair> pairs;
  const fcl::CollisionRequestd request(std::numeric_limits<std::size_t>::max(), false);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      if (!models_->object[a] || !models_->object[b]) continue;
      if (world.bodies[a].passive && world.bodies[b].passive) continue;
      fcl::CollisionResultd result;
      fcl::collide(models_->object[a].get(), models_->object[b].get(), request, result);
      for (std::size_t k = 0; k < result.numContacts(); ++k) {
        const fcl::Contactd& c = result.getContact(k);
        pairs.push_back({static_cast<std::int32_t>(a), static_cast<std::int32_t>(b), static_cast<std::int32_t>(c.b1),
                         static_cast<std::int32_t>(c.b2)});
      }
    }
  std::sort(pairs.begin(), pairs.end(), [](const TrianglePair& p, const TrianglePair& q) {
    return std::tie(p.a, p.b, p.triangle_a, p.triangle_b) < std::tie(q.a, q.b, q.triangle_a, q.triangle_b);
  });
  return pairs;
}

}  // namespace tcb
