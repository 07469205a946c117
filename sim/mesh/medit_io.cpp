#include "sim/mesh/medit_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <string>

#include "sim/io/atomic_file.hpp"
#include "sim/io/input_error.hpp"
#include "sim/io/token_reader.hpp"
#include "sim/mesh/hex_split.hpp"

namespace tcb {
namespace {

constexpr std::int64_t kMaxCount = std::numeric_limits<std::int32_t>::max();

// One element's vertex indices; its reference goes to `part`.
template <std::size_t N>
std::array<std::int32_t, N> read_element(TokenReader& in, std::int64_t vertex_count, const char* section,
                                         std::int32_t& part) {
  std::array<std::int32_t, N> e{};
  for (std::size_t k = 0; k < N; ++k) {
    const int line = in.peek_line();
    const std::int64_t index = in.next_int("a vertex index", std::numeric_limits<std::int64_t>::min(),
                                           std::numeric_limits<std::int64_t>::max());
    if (index < 1 || index > vertex_count)
      in.fail(line, std::string(section) + ": vertex index " + std::to_string(index) +
                        " is outside 1.." + std::to_string(vertex_count));
    e[k] = static_cast<std::int32_t>(index - 1);
  }
  const int line = in.peek_line();
  const std::int64_t reference = in.next_reference("an element reference");
  if (reference < std::numeric_limits<std::int32_t>::min() || reference > std::numeric_limits<std::int32_t>::max())
    in.fail(line, std::string(section) + ": element reference " + std::to_string(reference) +
                      " is outside the 32-bit range parts are kept in");
  part = static_cast<std::int32_t>(reference);
  return e;
}

std::int64_t read_count(TokenReader& in, const std::string& section) {
  return in.next_int(("the element count of " + section).c_str(), 0, kMaxCount);
}

}  // namespace

TetMesh parse_medit(const std::string& file_name, std::string text, MeditReadStats* stats) {
  TokenReader in(file_name, std::move(text));
  std::vector<Vec3> vertices;
  std::vector<Tet> tets;
  std::vector<Hex> hexes;
  std::vector<std::int32_t> tet_parts, hex_parts;  // element references
  bool have_vertices = false;
  int vertices_line = 0;

  while (!in.at_end()) {
    const int line = in.peek_line();
    const std::string keyword(in.next("a section keyword"));
    if (keyword == "End") break;
    if (keyword == "MeshVersionFormatted") {
      in.next_int("the format version", 1, 3);
    } else if (keyword == "Dimension") {
      const std::int64_t dim = in.next_int("the dimension", 0, 1000);
      if (dim != 3) in.fail(line, "only 3D meshes are supported (Dimension " + std::to_string(dim) + ")");
    } else if (keyword == "Vertices") {
      if (have_vertices) in.fail(line, "second Vertices section");
      have_vertices = true;
      vertices_line = line;
      const std::int64_t n = read_count(in, keyword);
      vertices.reserve(in.reservable(n, 8));  // "x y z r": at least 8 characters
      for (std::int64_t i = 0; i < n; ++i) {
        const double x = in.next_double("a vertex x coordinate");
        const double y = in.next_double("a vertex y coordinate");
        const double z = in.next_double("a vertex z coordinate");
        in.next_reference("a vertex reference");
        vertices.emplace_back(x, y, z);
      }
    } else if (keyword == "Tetrahedra" || keyword == "Hexahedra") {
      if (!have_vertices) in.fail(line, keyword + " before Vertices");
      const std::int64_t n = read_count(in, keyword);
      const auto nv = static_cast<std::int64_t>(vertices.size());
      for (std::int64_t i = 0; i < n; ++i) {
        std::int32_t part = 0;
        if (keyword == "Tetrahedra") {
          tets.push_back(read_element<4>(in, nv, "Tetrahedra", part));
          tet_parts.push_back(part);
        } else {
          hexes.push_back(read_element<8>(in, nv, "Hexahedra", part));
          hex_parts.push_back(part);
        }
      }
    } else if (!looks_numeric(keyword)) {
      // A section we do not use: skip its numbers up to the next keyword.
      while (!in.at_end() && looks_numeric(in.peek())) in.next("a number");
    } else {
      in.fail(line, "expected a section keyword, found '" + keyword + "'");
    }
  }
  if (!have_vertices) in.fail(0, "no Vertices section");
  if (tets.empty() && hexes.empty()) in.fail(vertices_line, "no Tetrahedra or Hexahedra: not a volume mesh");
  if (stats) stats->hexahedra = static_cast<std::int64_t>(hexes.size());
  if (!hexes.empty()) {
    const std::vector<Tet> split = split_hexahedra(hexes);
    tets.insert(tets.end(), split.begin(), split.end());
    for (const std::int32_t part : hex_parts) tet_parts.insert(tet_parts.end(), split.size() / hexes.size(), part);
  }
  try {
    TetMesh mesh = build_tet_mesh(std::move(vertices), std::move(tets));
    if (std::adjacent_find(tet_parts.begin(), tet_parts.end(), std::not_equal_to<>()) != tet_parts.end())
      mesh.tet_part = std::move(tet_parts);  // one reference throughout: no parts
    return mesh;
  } catch (const MeshError& e) {
    throw InputError(file_name, 0, e.what());
  }
}

TetMesh read_medit(const std::filesystem::path& path, MeditReadStats* stats) {
  return parse_medit(path.string(), read_file(path), stats);
}

void write_medit(const std::filesystem::path& path, const TetMesh& mesh) {
  AtomicFile file(path);
  auto& out = file.stream();
  out << "MeshVersionFormatted 2\nDimension 3\n";
  out << "Vertices\n" << mesh.positions_m.size() << "\n";
  for (const Vec3& p : mesh.positions_m) out << fmt::format("{} {} {} 0\n", p.x(), p.y(), p.z());
  out << "Tetrahedra\n" << mesh.tets.size() << "\n";
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const Tet& t = mesh.tets[i];
    out << fmt::format("{} {} {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1,
                       mesh.tet_part.empty() ? 0 : mesh.tet_part[i]);
  }
  out << "Triangles\n" << mesh.surface.size() << "\n";
  for (const Triangle& f : mesh.surface) out << fmt::format("{} {} {} 0\n", f[0] + 1, f[1] + 1, f[2] + 1);
  out << "End\n";
  file.commit();
}

}  // namespace tcb
