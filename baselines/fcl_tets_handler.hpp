#pragma once
/// `fcl_tets`: the collision handling a practitioner would build on FCL, as
/// the baseline a user of FCL would compare the paper's method with. Every
/// tet of every body that can collide is an FCL Convex (4 vertices, 4
/// faces) in one DynamicAABBTreeCollisionManager, refitted every step to the
/// current positions (passive fixed bodies once). The broad phase yields tet
/// pairs with overlapping boxes; pairs of bodies that cannot collide are
/// dropped, as are pairs of one body without self-collision and pairs of
/// tets sharing a vertex. Each remaining pair, in (body, tet) order, goes to
/// libccd's GJK + EPA (ccdGJKPenetration), called directly: FCL 0.7's own
/// libccd path for two Convex shapes runs MPR (ccdMPRPenetration), whose
/// depth is measured along the line between the shapes' centres, an
/// estimate, and would need Convex's interior point rebuilt whenever a tet
/// deforms; EPA gives the minimum translation that separates the two tets
/// (to a tolerance of 1e-6 mean edge lengths). A pair whose depth is within
/// that tolerance is touching, not penetrating, and no contact (the plates'
/// shared faces come out of EPA at 1e-17 m). This is the library's
/// tolerance, not an exact decision: the baseline is what FCL gives its users.
///
/// Response: a pair with depth d, direction n (moving tet b by d n separates
/// them) and contact point p is one penalty contact with the pair's response
/// parameters (method/response/penalty_response.hpp), spread over the two
/// tets by p's barycentric weights: the force on tet a acts on its vertex i
/// as a point-in-tet contact (vertex i of a against tet b at p's weights in
/// b) with stiffness and damping scaled by a's weight w_i of p. The normal
/// forces sum to the pair's k d - c v_n (v_n the relative normal velocity of
/// p) while none of the four would pull, and the reactions sum to minus that:
/// momentum is conserved. Under implicit response the four are contact links,
/// solved with the bodies like every other method's contacts.
///
/// What it reports (contacts(), for recall, precision and depth error
/// against the oracle): the vertices of both tets of every contact pair, each
/// with the deepest of its pairs' depths. So a vertex counts as found when a
/// tet containing it is in a colliding pair with a tet of its partner; every
/// point the oracle finds inside a tet is found (a tet around it overlaps
/// that tet), and precision counts the vertices of colliding tets that lie
/// outside, which is what a tet-pair method knows.
///
/// Budget: refitting the tree is one task (it cannot stop halfway; it charges
/// one work unit per tet refitted); then the pair loop stops as soon as the
/// budget is spent, one work unit per pair, and the pairs not reached get no
/// force this step (no extrapolation: what a user capping FCL would do).
/// Its work units count tets and pairs, not the collision cycle's
/// operations: compare it with the other methods under wall budgets.

#include <memory>

#include "method/handler/collision_handler.hpp"

namespace tcb {

class FclTetsHandler final : public CollisionHandler {
 public:
  FclTetsHandler();
  ~FclTetsHandler() override;
  void init(const World& world, const CollisionSettings& settings) override;
  StepReport step(World& world, Budget& budget) override;
  const std::vector<Contact>& contacts() const override;

 private:
  struct Impl;  // FCL and libccd stay in the .cpp
  std::unique_ptr<Impl> m;
};

}  // namespace tcb
