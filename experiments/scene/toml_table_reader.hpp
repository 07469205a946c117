#pragma once
// Strict reading of TOML tables for tcbench's input files (scenes, sweeps,
// thresholds): typed getters with range checks, errors that name the file and
// the line (or the --set that made a value), and unknown keys rejected.
// Internal to experiments/ (toml++ stays out of every other folder).

#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sim/io/input_error.hpp"
#include "sim/mesh/tet_mesh.hpp"

namespace tcb {

// Where a node came from: the scene file, or the --set override that made it.
// toml++ does not copy source regions with nodes, so the nodes that overrides
// inserted are remembered here.
struct Where {
  std::string file;
  int line;
};

struct Origins {
  std::string file;
  std::map<const toml::node*, std::string> overridden;  // node -> "--set key=value"
};

inline Where where_of(const toml::node& node, const Origins& origins) {
  if (auto it = origins.overridden.find(&node); it != origins.overridden.end()) return {it->second, 0};
  return {origins.file, static_cast<int>(node.source().begin.line)};
}

// Reads the keys of one table with type and range checks, remembering which
// keys it used so finish() can reject the rest as unknown.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string context, const Origins& file)
      : m_table(table), m_context(std::move(context)), m_file(file) {}

  const toml::node* node(std::string_view key) {
    m_known.insert(std::string(key));
    return m_table.get(key);
  }

  [[noreturn]] void fail(std::string_view key, const std::string& problem) const {
    const toml::node* n = m_table.get(key);
    const Where w = n ? where_of(*n, m_file) : where_of(m_table, m_file);
    throw InputError(w.file, w.line, m_context + "." + std::string(key) + ": " + problem);
  }

  std::optional<double> number(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_number()) fail(key, "must be a number");
    const double v = *n->value<double>();
    if (!std::isfinite(v)) fail(key, "must be finite");
    return v;
  }
  double positive(std::string_view key, double fallback) {
    const auto v = number(key);
    if (v && !(*v > 0.0)) fail(key, "must be positive");
    return v.value_or(fallback);
  }
  double non_negative(std::string_view key, double fallback) {
    const auto v = number(key);
    if (v && *v < 0.0) fail(key, "must not be negative");
    return v.value_or(fallback);
  }
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t min_value, std::int64_t max_value) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_integer()) fail(key, "must be a whole number");
    const std::int64_t v = *n->value<std::int64_t>();
    if (v < min_value || v > max_value)
      fail(key, "must lie in [" + std::to_string(min_value) + ", " + std::to_string(max_value) + "]");
    return v;
  }
  std::optional<bool> boolean(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_boolean()) fail(key, "must be true or false");
    return *n->value<bool>();
  }
  std::optional<std::string> string(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "must be a string");
    return *n->value<std::string>();
  }
  std::optional<Vec3> vec3(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3) fail(key, "must be an array of three numbers");
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      if (!(*a)[k].is_number()) fail(key, "must be an array of three numbers");
      v[k] = *(*a)[k].value<double>();
      if (!std::isfinite(v[k])) fail(key, "must be finite");
    }
    return v;
  }
  /// An array of strings (a lone string counts as a list of one).
  std::optional<std::vector<std::string>> string_list(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    std::vector<std::string> out;
    if (n->is_string()) return std::vector<std::string>{*n->value<std::string>()};
    const toml::array* a = n->as_array();
    if (!a) fail(key, "must be a string or an array of strings");
    for (const auto& e : *a) {
      if (!e.is_string()) fail(key, "must be a string or an array of strings");
      out.push_back(*e.value<std::string>());
    }
    return out;
  }
  const toml::table* table(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, "must be a table");
    return n->as_table();
  }
  int line_of(std::string_view key) const {
    const toml::node* n = m_table.get(key);
    return n ? where_of(*n, m_file).line : where_of(m_table, m_file).line;
  }

  void finish() const {
    for (auto&& [key, value] : m_table) {
      if (m_known.count(std::string(key.str()))) continue;
      std::string known;
      for (const auto& k : m_known) known += (known.empty() ? "" : ", ") + k;
      const Where w = where_of(value, m_file);
      throw InputError(w.file, w.line,
                       "unknown key '" + std::string(key.str()) + "' in " + m_context + " (known: " + known + ")");
    }
  }

 private:
  const toml::table& m_table;
  std::string m_context;
  const Origins& m_file;
  std::set<std::string> m_known;
};


/// Parses TOML text; `path` names it in errors; a syntax error is an InputError at its line.
inline toml::table parse_toml_text(std::string_view text, const std::filesystem::path& path) {
  try {
    return toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    throw InputError(path.string(), static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
}

/// Parses a whole TOML file; a syntax error is an InputError at its line.
inline toml::table parse_toml_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path.string(), 0, "is a directory, not a file");
  try {
    return toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    const int line = static_cast<int>(e.source().begin.line);
    if (!std::filesystem::exists(path)) throw InputError(path.string(), 0, "no such file");
    throw InputError(path.string(), line, std::string(e.description()));
  }
}

}  // namespace tcb
