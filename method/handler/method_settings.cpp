#include "method/handler/method_settings.hpp"

#include <fmt/format.h>

namespace tcb {

MethodSettings::MethodSettings(const std::vector<SettingSpec>& schema) {
  for (const SettingSpec& s : schema) m_values[s.name] = s.default_value;
}

const char* to_string(SettingSpec::Type type) {
  switch (type) {
    case SettingSpec::Type::Integer: return "integer";
    case SettingSpec::Type::Number: return "number";
    case SettingSpec::Type::Boolean: return "boolean";
    case SettingSpec::Type::String: return "string";
  }
  return "?";
}

std::string format_setting(const SettingValue& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) {  // a TOML basic string
          std::string quoted = "\"";
          for (const char c : v) {
            if (c == '"' || c == '\\') quoted += '\\';
            quoted += c;
          }
          return quoted + "\"";
        }
        else return fmt::format("{}", v);
      },
      value);
}

std::string method_label(const std::string& method, const std::vector<SettingSpec>& schema,
                         const MethodSettings& settings) {
  std::string changed;
  for (const SettingSpec& s : schema) {
    const auto it = settings.values().find(s.name);
    if (it == settings.values().end() || it->second == s.default_value) continue;
    changed += fmt::format("{}{}={}", changed.empty() ? "" : ",", s.name, format_setting(it->second));
  }
  return changed.empty() ? method : method + "(" + changed + ")";
}

}  // namespace tcb
