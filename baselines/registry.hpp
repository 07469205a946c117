#pragma once
/// The list of collision handling methods: what `tcbench list methods` prints,
/// what `--method` accepts, what sweeps iterate over, and what the
/// cross-method tests check (every method, unlimited budget, must find exactly
/// brute_force's colliding points). Adding a method: one file in baselines/
/// (or method/) and one entry in registry.cpp.

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "method/handler/collision_handler.hpp"

namespace tcb {

struct MethodInfo {
  std::string name;
  std::string description;
  std::vector<std::string> settings;  ///< keys accepted in the method's scene table
  /// Builds the handler from its settings (validated: unknown keys and bad
  /// values throw InputError naming where they were written).
  std::function<std::unique_ptr<CollisionHandler>(const std::map<std::string, MethodSetting>&)> make;
  bool detects = true;  ///< false for `none`: it is exempt from the cross-method test
  bool uses_budget = false;  ///< true when a budget changes what it does (sweeps run the others once)
};

const std::vector<MethodInfo>& method_registry();

/// The handler for `name` with the scene's settings for it; InputError for an
/// unknown name or bad settings. The handler is not yet init()ed.
std::unique_ptr<CollisionHandler> make_handler(const std::string& name, const SceneDesc& scene);

}  // namespace tcb
