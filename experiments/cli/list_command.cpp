// tcbench list methods|scenes
#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>
#include <set>

#include "experiments/cli/command.hpp"
#include "baselines/registry.hpp"
#include "experiments/scene/scene_file.hpp"

namespace tcb::cli {
namespace {

class ListCommand final : public Command {
 public:
  explicit ListCommand(CLI::App& parent) {
    app = parent.add_subcommand("list", "List the collision handling methods or the named scenes");
    app->add_option("WHAT", m_what, "methods or scenes")->required()->check(CLI::IsMember({"methods", "scenes"}));
  }

  int execute() override {
    if (m_what == "methods") {
      for (const MethodInfo& m : method_registry()) {
        std::cout << fmt::format("{:<32} {}\n", m.name, m.description);
        for (const SettingSpec& s : m.settings)  // [method.NAME] keys, as scenes and sweeps write them
          std::cout << fmt::format("{:<32}   method.{}.{} ({}, default {}): {}\n", "", m.name, s.name,
                                   to_string(s.type), format_setting(s.default_value), s.description);
      }
      return 0;
    }
    std::set<std::string> seen;
    for (const auto& dir : default_scene_dirs()) {
      if (!std::filesystem::is_directory(dir)) continue;
      std::set<std::filesystem::path> files;
      for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".toml") files.insert(entry.path());
      for (const auto& file : files) {
        const std::string name = file.stem().string();
        if (!seen.insert(name).second) continue;  // an earlier directory shadows it
        std::string description;
        try {
          description = toml::parse_file(file.string())["scene"]["description"].value_or(std::string());
        } catch (const toml::parse_error& e) {
          description = fmt::format("(unreadable: line {}: {})", e.source().begin.line, e.description());
        }
        std::cout << fmt::format("{:<24} {}\n", name, description);
      }
    }
    return 0;
  }

 private:
  std::string m_what;
};

}  // namespace

std::unique_ptr<Command> make_list_command(CLI::App& parent) { return std::make_unique<ListCommand>(parent); }

}  // namespace tcb::cli
