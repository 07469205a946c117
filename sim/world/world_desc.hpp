#pragma once
/// The simulated world a scene asks for, as plain data (parsed from TOML by
/// experiments/), and build_world(), which builds exactly that and nothing
/// more: only the named objects, a ground only when the scene has one, no
/// model for passive objects. Collision handling and the run's own settings
/// are not here: sim/ cannot interpret them (method/handler/collision_settings.hpp,
/// experiments/scene/scene_desc.hpp).
///
/// Stacks: an object with stack.count = N > 1 becomes N copies named
/// NAME_00 .. NAME_{N-1}, placed along stack.axis one extent apart (plus
/// stack.gap). The copies touch exactly: the mesh is first shifted so its
/// lowest coordinate on the axis is exactly 0, copy i+1 is placed at
/// p_{i+1} = p_i + extent, and so the top face of copy i (extent + p_i) and the
/// bottom face of copy i+1 (0 + p_{i+1}) are the same doubles. This is the
/// face-on-face stack of the paper (plates20), where every step the collision
/// stages meet points exactly on faces. stack.stagger shifts every odd copy
/// sideways: with side faces exactly aligned too, whole rows of vertices lie
/// exactly on the neighbour's side faces, where any consistent tie-break puts
/// them outside from both sides, so those edges would carry no contact.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/world/world.hpp"

namespace tcb {

struct StackDesc {
  int count = 1;
  int axis = 1;  ///< 0 x, 1 y, 2 z
  double gap_m = 0.0;
  /// Added to every odd copy, across the stacking axis (its component along
  /// the axis must be 0, so faces still touch exactly).
  Vec3 stagger_m = Vec3::Zero();
};

/// The names of the bodies an object becomes: its own name, or with a stack
/// of count > 1 NAME_00, NAME_01, ... (two digits at least).
std::vector<std::string> body_names(const std::string& object_name, const StackDesc& stack);

struct ObjectDesc {
  std::string name;
  std::string mesh;                 ///< file path (relative to base_dir) or generator string
  /// Where `mesh` was given when not in the scene file ("--set object.0.mesh=..."),
  /// so a mesh that cannot be loaded is blamed there; empty: the object's line.
  std::string mesh_origin;
  std::filesystem::path base_dir;   ///< the scene file's folder
  int source_line = 0;              ///< where the object is declared, for errors
  Vec3 position_m = Vec3::Zero();   ///< translation applied after scaling
  double scale = 1.0;
  Vec3 velocity_m_per_s = Vec3::Zero();
  bool passive = false;
  bool self_collision = false;
  Material material;
  StackDesc stack;
  /// A trajectory CSV (relative to base_dir): the object is driven along it
  /// (its position over time, replacing position_m), is passive, and its
  /// contact forces are the run's probe force. Empty: not driven.
  std::string trajectory;
  /// A latent path CSV (relative to base_dir; latent/latent_path.hpp): the
  /// object, whose mesh must be a latent family ("finger:finger_small"), is
  /// driven through the shapes of the path's codes, and is passive. Empty:
  /// not latent-driven.
  std::string latent_path;
  /// The network trained for the family (relative to base_dir), for the
  /// `neural` method; empty: none.
  std::string latent_model;
};

/// How the vertices of a file's mesh are numbered in the simulation.
enum class MeshOrder {
  File,   ///< as the file numbers them (the default, and the paper's runs)
  Curve,  ///< renumbered along a Morton curve at load (sim/mesh/curve_numbering.hpp)
};

/// The scene file's and run.json's spelling: "file" or "curve".
inline const char* to_string(MeshOrder order) { return order == MeshOrder::Curve ? "curve" : "file"; }

struct WorldDesc {
  std::filesystem::path path;  ///< the file it came from, for errors (empty when built in code)
  /// Applies to meshes read from files and to generated boxes; a latent
  /// family's mesh ("finger:...") keeps its own numbering, which its
  /// skinning is defined in. Outputs stay in the file's numbering either way.
  MeshOrder mesh_order = MeshOrder::File;
  double dt_s = 1.0e-3;        ///< the step the world is integrated with
  Vec3 gravity_m_per_s2 = Vec3(0.0, -9.81, 0.0);
  std::optional<GroundPlane> ground;
  std::vector<ObjectDesc> objects;
};

/// Mesh sources: a file or a box generator (sim/mesh/load_mesh.hpp), or
/// "finger:PRESET", the rest mesh of a skinned finger preset
/// (latent/skinned_finger.hpp), parts = bones.
/// Loads each distinct mesh once and builds the world. Throws InputError for a
/// mesh that cannot be loaded (naming the mesh file, or the scene line when
/// the problem is the source string itself).
/// The largest coordinate magnitude a scaled mesh may have (m): the range in
/// which orient3d stays exact (sim/geometry/orient3d.hpp).
inline constexpr double kMaxCoordinate_m = 1e90;

World build_world(const WorldDesc& desc);

}  // namespace tcb
