#pragma once
/// `none`: no collision handling at all. Objects pass through each other; the
/// ground still holds them. The floor every other method is compared with.

#include "method/handler/collision_handler.hpp"

namespace tcb {

class NoneHandler final : public CollisionHandler {
 public:
  void init(const World&, const CollisionSettings&) override {}
  StepReport step(World&, Budget&) override { return {}; }
  const std::vector<Contact>& contacts() const override { return m_none; }

 private:
  std::vector<Contact> m_none;
};

}  // namespace tcb
