#pragma once
/// Typed settings of a collision handling method: the schema a method
/// declares (name, type, default, range, meaning) and the values a run
/// resolved against it. Readers of scene and sweep files check values against
/// the schema (experiments/scene/method_settings_reader.hpp) before a handler
/// is built, so a handler only ever sees valid, complete values: every key of
/// its schema, defaults filled in.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace tcb {

using SettingValue = std::variant<std::int64_t, double, bool, std::string>;

/// One setting of a method's schema.
struct SettingSpec {
  enum class Type { Integer, Number, Boolean, String };
  std::string name;
  Type type = Type::Integer;
  SettingValue default_value = std::int64_t{0};
  /// Closed range for Integer and Number settings.
  double min = -1e300, max = 1e300;
  std::string description;
};

/// A method's resolved settings: one value per key of its schema.
class MethodSettings {
 public:
  MethodSettings() = default;
  /// The schema's defaults.
  explicit MethodSettings(const std::vector<SettingSpec>& schema);

  void set(const std::string& name, SettingValue value) { m_values[name] = std::move(value); }
  std::int64_t integer(const std::string& name) const { return std::get<std::int64_t>(m_values.at(name)); }
  double number(const std::string& name) const { return std::get<double>(m_values.at(name)); }
  bool boolean(const std::string& name) const { return std::get<bool>(m_values.at(name)); }
  const std::string& string(const std::string& name) const { return std::get<std::string>(m_values.at(name)); }
  const std::map<std::string, SettingValue>& values() const { return m_values; }

 private:
  std::map<std::string, SettingValue> m_values;
};

/// "integer", "number", "boolean" or "string".
const char* to_string(SettingSpec::Type type);

/// A value as TOML would write it (4, 0.5, true, "text").
std::string format_setting(const SettingValue& value);

/// The method's name with the settings that differ from the schema's
/// defaults, in schema order: "every_nth(n=4)"; just the name when all are
/// defaults. The one label runs are grouped and plotted by.
std::string method_label(const std::string& method, const std::vector<SettingSpec>& schema,
                         const MethodSettings& settings);

}  // namespace tcb
