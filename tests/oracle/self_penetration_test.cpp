// A body's self-penetration label (oracle/self_penetration.hpp) on the
// skinned finger: equal to the brute-force part-aware depths on random codes,
// true on strong curls and false at rest.
#include "oracle/self_penetration.hpp"

#include <catch2/catch.hpp>

#include <cmath>

#include "method/neural/active_learning.hpp"
#include "oracle/tet_inside.hpp"
#include "sim/latent/skinned_finger.hpp"
#include "tests/oracle/brute_self_depth.hpp"

using namespace tcb;

namespace {

Body finger_body(const SkinnedFinger& finger, const Eigen::VectorXd& z) {
  Body body;
  body.name = "finger";
  body.mesh = finger.mesh();
  body.x_m = finger.decode(z);
  body.self_collision = true;
  return body;
}

}  // namespace

TEST_CASE("self penetration: equals the brute-force part-aware depths on random finger codes", "[oracle][neural]") {
  const SkinnedFinger finger(finger_preset("finger_small"));
  int penetrating = 0;
  for (std::uint64_t i = 0; i < 12; ++i) {
    const Eigen::VectorXd z = neural::uniform_code(finger.latent_size(), 2024, 0, i);
    const Body body = finger_body(finger, z);
    const SelfPenetration p = self_penetration(body);
    // Every vertex a candidate: the brute force decides inside by itself.
    const std::vector<double> depth =
        test::brute_force_depths(body, std::vector<TetSide>(body.x_m.size(), TetSide::Inside));
    double pd = 0.0;
    std::int64_t deep = 0;
    std::vector<double> part_pd(p.part_pd_m.size(), 0.0);
    const TetMesh& mesh = *body.mesh;
    for (std::size_t v = 0; v < depth.size(); ++v) {
      if (std::isnan(depth[v])) continue;
      ++deep, pd = std::max(pd, depth[v]);
      for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (const std::int32_t u : mesh.tets[t])
          if (u == static_cast<std::int32_t>(v)) {
            double& d = part_pd[static_cast<std::size_t>(mesh.tet_part[t])];
            d = std::max(d, depth[v]);
          }
    }
    INFO("code " << i);
    CHECK(p.deep == deep);
    CHECK(p.penetrates == (deep > 0));
    CHECK(p.pd_m == Approx(pd).margin(1e-12).epsilon(1e-12));
    for (std::size_t a = 0; a < part_pd.size(); ++a)
      CHECK(p.part_pd_m[a] == Approx(part_pd[a]).margin(1e-12).epsilon(1e-12));
    penetrating += p.penetrates;
  }
  CHECK(penetrating > 0);   // the sample exercises both answers
  CHECK(penetrating < 12);
}

TEST_CASE("self penetration: the rest pose does not penetrate, a full curl does", "[oracle][neural]") {
  for (const char* preset : {"finger_small", "finger_large"}) {
    const SkinnedFinger finger(finger_preset(preset));
    INFO(preset);
    const SelfPenetration rest = self_penetration(finger_body(finger, finger.rest_code()));
    CHECK_FALSE(rest.penetrates);
    CHECK(rest.pd_m == 0.0);
    const SelfPenetration curl = self_penetration(finger_body(finger, finger.full_curl_code()));
    CHECK(curl.penetrates);
    CHECK(curl.pd_m > 0.0);
  }
}
