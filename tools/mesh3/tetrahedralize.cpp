// tcbench_mesh3: tetrahedralizes an implicit sphere or torus, or a closed
// triangle surface (OBJ/OFF), with CGAL Mesh_3, and writes MEDIT .mesh through
// tcbench's own writer (so orientation and surface are checked the same way as
// for every mesh the harness reads). Deterministic: CGAL's random generator is
// seeded.
//
//   tcbench_mesh3 sphere RADIUS SIZE OUT.mesh
//   tcbench_mesh3 torus MAJOR_RADIUS MINOR_RADIUS SIZE OUT.mesh   (axis y)
//   tcbench_mesh3 surface IN.obj SIZE OUT.mesh
// SIZE is the target edge length (facet and cell size), in the input's units.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Random.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

#include "sim/mesh/medit_io.hpp"
#include "sim/mesh/mesh_statistics.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using FT = K::FT;

template <typename Domain>
tcb::TetMesh mesh_domain(const Domain& domain, double size) {
  using Tr = typename CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
  using Criteria = CGAL::Mesh_criteria_3<Tr>;
  using namespace CGAL::parameters;
  CGAL::get_default_random() = CGAL::Random(20261121);
  const Criteria criteria(facet_angle = 25, facet_size = size, facet_distance = size / 8.0,
                          cell_radius_edge_ratio = 2.5, cell_size = size);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, odt(), lloyd(), perturb(), exude());

  std::map<typename Tr::Vertex_handle, std::int32_t> index;
  std::vector<tcb::Vec3> positions;
  std::vector<tcb::Tet> tets;
  for (auto cell = c3t3.cells_in_complex_begin(); cell != c3t3.cells_in_complex_end(); ++cell) {
    tcb::Tet tet;
    for (int k = 0; k < 4; ++k) {
      const auto v = cell->vertex(k);
      auto [it, added] = index.emplace(v, static_cast<std::int32_t>(positions.size()));
      if (added) {
        const auto p = v->point().point();
        positions.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
      }
      tet[k] = it->second;
    }
    tets.push_back(tet);
  }
  return tcb::build_tet_mesh(std::move(positions), std::move(tets));
}

int usage() {
  std::cerr << "usage: tcbench_mesh3 sphere RADIUS SIZE OUT.mesh\n"
               "       tcbench_mesh3 torus MAJOR_RADIUS MINOR_RADIUS SIZE OUT.mesh\n"
               "       tcbench_mesh3 surface IN.obj SIZE OUT.mesh\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string kind = argv[1];
  tcb::TetMesh mesh;
  std::string out;
  if (kind == "sphere" && argc == 5) {
    const double r = std::atof(argv[2]), size = std::atof(argv[3]);
    out = argv[4];
    using Domain = CGAL::Labeled_mesh_domain_3<K>;
    auto f = [r](const Point& p) { return FT(p.x() * p.x() + p.y() * p.y() + p.z() * p.z() - r * r); };
    mesh = mesh_domain(Domain::create_implicit_mesh_domain(f, K::Sphere_3(CGAL::ORIGIN, FT(4 * r * r))), size);
  } else if (kind == "torus" && argc == 6) {
    const double major = std::atof(argv[2]), minor = std::atof(argv[3]), size = std::atof(argv[4]);
    out = argv[5];
    using Domain = CGAL::Labeled_mesh_domain_3<K>;
    auto f = [major, minor](const Point& p) {
      const double ring = std::sqrt(p.x() * p.x() + p.z() * p.z()) - major;
      return FT(ring * ring + p.y() * p.y() - minor * minor);
    };
    const double bound = major + 2 * minor;
    mesh = mesh_domain(Domain::create_implicit_mesh_domain(f, K::Sphere_3(CGAL::ORIGIN, FT(bound * bound))), size);
  } else if (kind == "surface" && argc == 5) {
    using Polyhedron = CGAL::Polyhedron_3<K>;
    Polyhedron surface;
    if (!CGAL::IO::read_polygon_mesh(argv[2], surface) || !surface.is_closed()) {
      std::cerr << argv[2] << ": cannot read a closed triangle surface\n";
      return 2;
    }
    out = argv[4];
    mesh = mesh_domain(CGAL::Polyhedral_mesh_domain_3<Polyhedron, K>(surface), std::atof(argv[3]));
  } else {
    return usage();
  }
  tcb::write_medit(out, mesh);
  const tcb::MeshStatistics s = tcb::mesh_statistics(mesh);
  std::cout << out << ": " << s.vertices << " vertices, " << s.tets << " tets, " << s.surface_triangles
            << " surface triangles, volume " << s.volume_m3 << ", worst quality " << s.worst_quality
            << ", inverted " << s.inverted_tets << ", degenerate " << s.degenerate_tets << ", folds "
            << s.folded_faces << ", Euler characteristic " << s.surface_euler_characteristic << "\n";
  return 0;
}
