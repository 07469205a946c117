// tcbench mesh info FILE [--json] | tcbench mesh convert IN OUT
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>

#include "experiments/cli/command.hpp"
#include "sim/io/input_error.hpp"
#include "sim/mesh/load_mesh.hpp"
#include "sim/mesh/medit_io.hpp"
#include "sim/mesh/mesh_statistics.hpp"
#include "sim/mesh/vtu_writer.hpp"

namespace tcb::cli {
namespace {

class MeshCommand final : public Command {
 public:
  explicit MeshCommand(CLI::App& parent) {
    app = parent.add_subcommand("mesh", "Inspect or convert tetrahedral meshes");
    app->require_subcommand(1);
    m_info = app->add_subcommand("info", "Print sizes, volume, bounding box, quality and defects of a mesh");
    m_info->add_option("FILE", m_input, "A .mesh (MEDIT), .node/.ele (TetGen) file or a generator string")->required();
    m_info->add_flag("--json", m_json, "Print one JSON object instead of text");
    m_convert = app->add_subcommand("convert", "Convert a mesh; the output extension picks the format (.mesh, .vtu)");
    m_convert->add_option("IN", m_input, "Input mesh (any format mesh info reads)")->required();
    m_convert->add_option("OUT", m_output, "Output file: .mesh or .vtu")->required();
  }

  int execute() override { return m_info->parsed() ? info() : convert(); }

 private:
  int info() const {
    const TetMesh mesh = load_mesh(m_input);
    const MeshStatistics s = mesh_statistics(mesh);
    if (m_json) {
      nlohmann::ordered_json j;
      j["file"] = m_input;
      j["vertices"] = s.vertices;
      j["tets"] = s.tets;
      j["edges"] = s.edges;
      j["surface_triangles"] = s.surface_triangles;
      j["volume"] = s.volume_m3;
      j["bbox_min"] = {s.bbox_min.x(), s.bbox_min.y(), s.bbox_min.z()};
      j["bbox_max"] = {s.bbox_max.x(), s.bbox_max.y(), s.bbox_max.z()};
      j["average_edge"] = s.average_edge_m;
      j["worst_quality"] = s.worst_quality;
      j["mean_quality"] = s.mean_quality;
      j["inverted_tets"] = s.inverted_tets;
      j["degenerate_tets"] = s.degenerate_tets;
      j["folded_faces"] = s.folded_faces;
      j["isolated_vertices"] = s.isolated_vertices;
      j["surface_euler_characteristic"] = s.surface_euler_characteristic;
      j["parts"] = s.parts;
      std::cout << j.dump() << '\n';
      return 0;
    }
    std::cout << fmt::format(
        "file                 {}\n"
        "vertices             {}\n"
        "tets                 {}\n"
        "edges                {}\n"
        "surface triangles    {}  (Euler characteristic {})\n"
        "volume               {:.6g}\n"
        "bbox                 [{:.6g}, {:.6g}, {:.6g}] .. [{:.6g}, {:.6g}, {:.6g}]\n"
        "average edge         {:.6g}\n"
        "quality              worst {:.4g}, mean {:.4g}  (1 regular, 0 flat)\n"
        "inverted tets        {}  (given with negative orientation, repaired)\n"
        "degenerate tets      {}  (exactly flat, inert)\n"
        "folded faces         {}  (interior faces with both tets on one side)\n"
        "isolated vertices    {}\n"
        "parts                {}  (element references, box parts=; 1: none)\n",
        m_input, s.vertices, s.tets, s.edges, s.surface_triangles, s.surface_euler_characteristic, s.volume_m3,
        s.bbox_min.x(), s.bbox_min.y(), s.bbox_min.z(), s.bbox_max.x(), s.bbox_max.y(), s.bbox_max.z(),
        s.average_edge_m, s.worst_quality, s.mean_quality, s.inverted_tets, s.degenerate_tets, s.folded_faces,
        s.isolated_vertices, s.parts);
    return 0;
  }

  int convert() const {
    const std::filesystem::path out(m_output);
    const std::string ext = out.extension().string();
    if (ext != ".mesh" && ext != ".vtu")
      throw InputError(m_output, 0, "unknown output format '" + ext + "' (expected .mesh or .vtu)");
    const TetMesh mesh = load_mesh(m_input);
    if (ext == ".mesh") write_medit(out, mesh);
    else write_vtu(out, mesh.positions_m, mesh.tets);
    std::cout << fmt::format("wrote {} ({} vertices, {} tets)\n", m_output, mesh.vertex_count(), mesh.tet_count());
    return 0;
  }

  CLI::App* m_info = nullptr;
  CLI::App* m_convert = nullptr;
  std::string m_input, m_output;
  bool m_json = false;
};

}  // namespace

std::unique_ptr<Command> make_mesh_command(CLI::App& parent) { return std::make_unique<MeshCommand>(parent); }

}  // namespace tcb::cli
