#include "baselines/registry.hpp"

#include <cmath>

#include "baselines/every_nth_handler.hpp"
#include "baselines/full_handler.hpp"
#include "baselines/none_handler.hpp"
#include "method/handler/interruptible_handler.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {
namespace {

[[noreturn]] void bad_setting(const MethodSetting& s, const std::string& problem) {
  // `where` is "file:line" or "--set ..."; split the line back out for InputError.
  const auto colon = s.where.rfind(':');
  if (s.where.rfind("--set", 0) != 0 && colon != std::string::npos)
    throw InputError(s.where.substr(0, colon), std::stoi(s.where.substr(colon + 1)), problem);
  throw InputError(s.where, 0, problem);
}

int integer_setting(const std::map<std::string, MethodSetting>& settings, const std::string& key, int fallback,
                    int min_value) {
  const auto it = settings.find(key);
  if (it == settings.end()) return fallback;
  const double* v = std::get_if<double>(&it->second.value);
  if (!v || *v != std::floor(*v) || *v < min_value || *v > 1e6)
    bad_setting(it->second, key + " must be a whole number >= " + std::to_string(min_value));
  return static_cast<int>(*v);
}

bool bool_setting(const std::map<std::string, MethodSetting>& settings, const std::string& key, bool fallback) {
  const auto it = settings.find(key);
  if (it == settings.end()) return fallback;
  const bool* v = std::get_if<bool>(&it->second.value);
  if (!v) bad_setting(it->second, key + " must be true or false");
  return *v;
}

}  // namespace

const std::vector<MethodInfo>& method_registry() {
  static const std::vector<MethodInfo> registry = {
      {"interruptible", "seed 000: the cycle under a time budget, resumed next step, forces extrapolated meanwhile", {},
       [](const auto&) { return std::make_unique<InterruptibleHandler>(InterruptibleHandler::Stale::Extrapolate); }, true,
       true},
      {"interruptible_no_extrapolation", "ablation: interruptible without force extrapolation", {},
       [](const auto&) { return std::make_unique<InterruptibleHandler>(InterruptibleHandler::Stale::Nothing); }, true,
       true},
      {"interruptible_tracked",
       "variant (not in seed 000): interruptible, but contacts known from earlier steps get the penalty force of "
       "their depth tracked with the current positions instead of an extrapolated force",
       {},
       [](const auto&) { return std::make_unique<InterruptibleHandler>(InterruptibleHandler::Stale::Track); }, true,
       true},
      {"full", "the whole collision cycle every step, never interrupted (seed 000's reference)", {},
       [](const auto&) { return std::make_unique<FullHandler>(DetectionMode::SpatialHash); }, true},
      {"every_nth", "a full cycle every n-th step, the last forces held in between (every_nth.n, every_nth.hold)",
       {"n", "hold"},
       [](const auto& s) {
         return std::make_unique<EveryNthHandler>(integer_setting(s, "n", 2, 1), bool_setting(s, "hold", true));
       }, true},
      {"brute_force", "every point against every tet, no hashing: the O(n^2) reference for tests", {},
       [](const auto&) { return std::make_unique<FullHandler>(DetectionMode::BruteForce); }, true},
      {"none", "no collision handling: objects pass through each other (dynamics and ground only)", {},
       [](const auto&) { return std::make_unique<NoneHandler>(); }, false},
  };
  return registry;
}

std::unique_ptr<CollisionHandler> make_handler(const std::string& name, const SceneDesc& scene) {
  std::string names;
  for (const MethodInfo& m : method_registry()) {
    names += (names.empty() ? "" : ", ") + m.name;
    if (m.name != name) continue;
    static const std::map<std::string, MethodSetting> kEmpty;
    const auto it = scene.methods.find(name);
    const auto& settings = it == scene.methods.end() ? kEmpty : it->second;
    for (const auto& [key, value] : settings)
      if (std::find(m.settings.begin(), m.settings.end(), key) == m.settings.end())
        bad_setting(value, "unknown setting '" + key + "' of method " + name);
    return m.make(settings);
  }
  throw InputError("--method", 0, "unknown method '" + name + "' (available: " + names + ")");
}

}  // namespace tcb
