#pragma once
/// The list of collision handling methods: what `tcbench list methods` prints,
/// what `--method` accepts, what sweeps iterate over, and what the
/// cross-method tests check (every method, unlimited budget, must find exactly
/// brute_force's colliding points). Adding a method: its files in baselines/
/// (compiled by glob), one entry in registry.cpp, and its row (and its
/// settings' rows) in docs/contract.md, which a test checks.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "method/handler/collision_handler.hpp"
#include "method/handler/method_settings.hpp"

namespace tcb {

struct MethodInfo {
  std::string name;
  std::string description;
  /// The keys of its scene table [method.NAME] (and of a sweep's
  /// { name = "NAME", key = value } entry), typed, with defaults and ranges.
  std::vector<SettingSpec> settings = {};
  /// Builds the handler from settings already checked against `settings`.
  std::function<std::unique_ptr<CollisionHandler>(const MethodSettings&)> make;
  /// False for `none`: it detects nothing, so the cross-method test skips it.
  bool detects = true;
  /// True when a budget changes what it does; sweeps run the others once, budget none.
  bool uses_budget = false;
  /// What contacts() holds: the points inside a tet of another body (every
  /// method of the paper's kind), or the vertices of tets in colliding tet
  /// pairs (fcl_tets): a superset of the inside points wherever the pairs
  /// overlap in volume, so the cross-method test compares it as one.
  /// BodyVerdicts (neural): whether each latent-driven body collides with
  /// itself, no points; the cross-method test compares its verdict with
  /// brute_force's, as an approximation.
  enum class Reports { InsidePoints, TetPairVertices, BodyVerdicts } reports = Reports::InsidePoints;
};

const std::vector<MethodInfo>& method_registry();

/// The method of that name; InputError naming --method and listing the
/// methods when there is none.
const MethodInfo& find_method(const std::string& name);

/// The handler for `name` with these settings (the method's defaults when
/// omitted); not yet init()ed.
std::unique_ptr<CollisionHandler> make_handler(const std::string& name, const MethodSettings* settings = nullptr);

}  // namespace tcb
