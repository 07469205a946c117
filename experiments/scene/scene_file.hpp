#pragma once
/// Scene files (TOML, docs/contract.md "Scene files") into SceneDesc.
///
/// Strict: an unknown key, a value of the wrong type or out of range is an
/// InputError naming the file, the line and the key. Paths in the file are
/// relative to the file. `--set key=value` overrides are applied to the parsed
/// document before validation, so they are checked exactly like the file:
///   scene.dt=0.002                         a key of a table
///   object.plate.material.youngs_modulus=2e5   an object by name ...
///   object.0.scale=2                       ... or by index
///   ground.height=0.1                      creates [ground] if absent
///   method.every_nth.n=3                   a method's setting ([method.every_nth])
/// The value is read as TOML (numbers, booleans, arrays, "strings"); a bare
/// word that is not TOML is taken as a string (model=mass_spring).

#include <filesystem>
#include <string>
#include <vector>

#include "experiments/scene/scene_desc.hpp"

namespace tcb {

/// Loads a scene file with overrides ("key=value" strings).
SceneDesc load_scene_file(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});

/// The same from text; `path` names the file in errors and anchors relative paths.
SceneDesc parse_scene(const std::string& text, const std::filesystem::path& path,
                      const std::vector<std::string>& overrides = {});

/// Resolves SCENE as given on the command line: a path to a .toml file, or a
/// name looked up in the scene directories (the first that has NAME.toml).
std::filesystem::path resolve_scene(const std::string& scene, const std::vector<std::filesystem::path>& scene_dirs);

/// Scene directories: $TCBENCH_SCENES (colon-separated) if set, then the
/// source tree's experiments/scenes.
std::vector<std::filesystem::path> default_scene_dirs();

}  // namespace tcb
