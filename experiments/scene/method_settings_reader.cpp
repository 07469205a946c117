#include "experiments/scene/method_settings_reader.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace tcb {

MethodSettings read_method_settings(TableReader& reader, const MethodInfo& method) {
  MethodSettings settings(method.settings);
  for (const SettingSpec& spec : method.settings) {
    switch (spec.type) {
      case SettingSpec::Type::Integer:
        // The schema's range clamped to what an int64 holds (the defaults are +-1e300).
        if (const auto v = reader.integer(spec.name, static_cast<std::int64_t>(std::clamp(spec.min, -9.0e18, 9.0e18)),
                                          static_cast<std::int64_t>(std::clamp(spec.max, -9.0e18, 9.0e18))))
          settings.set(spec.name, *v);
        break;
      case SettingSpec::Type::Number:
        if (const auto v = reader.number(spec.name)) {
          if (*v < spec.min || *v > spec.max)
            reader.fail(spec.name, fmt::format("must lie in [{}, {}]", spec.min, spec.max));
          settings.set(spec.name, *v);
        }
        break;
      case SettingSpec::Type::Boolean:
        if (const auto v = reader.boolean(spec.name)) settings.set(spec.name, *v);
        break;
      case SettingSpec::Type::String:
        if (const auto v = reader.string(spec.name)) settings.set(spec.name, *v);
        break;
    }
  }
  return settings;
}

}  // namespace tcb
