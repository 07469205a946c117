#include "sim/mesh/vtu_writer.hpp"

#include <fmt/format.h>

#include "sim/io/atomic_file.hpp"

namespace tcb {

void write_vtu(const std::filesystem::path& path, const std::vector<Vec3>& x,
               const std::vector<Tet>& tets, const std::vector<VtuPointVectors>& point_data) {
  constexpr int kVtkTetra = 10;
  AtomicFile file(path);
  auto& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n"
      << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", x.size(), tets.size());
  out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3& p : x) out << fmt::format("{} {} {}\n", p.x(), p.y(), p.z());
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const Tet& t : tets) out << fmt::format("{} {} {} {}\n", t[0], t[1], t[2], t[3]);
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < tets.size(); ++i) out << 4 * (i + 1) << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < tets.size(); ++i) out << kVtkTetra << '\n';
  out << "</DataArray>\n</Cells>\n";
  if (!point_data.empty()) {
    out << "<PointData>\n";
    for (const auto& data : point_data) {
      out << fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">\n",
                         data.name);
      for (const Vec3& v : *data.values) out << fmt::format("{} {} {}\n", v.x(), v.y(), v.z());
      out << "</DataArray>\n";
    }
    out << "</PointData>\n";
  }
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdFrame>& frames) {
  AtomicFile file(path);
  auto& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& f : frames)
    out << fmt::format("<DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>\n", f.time_s, f.file);
  out << "</Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace tcb
