#include "sim/mesh/box_mesh.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace tcb {
namespace {

double grid_coordinate(double lo, double hi, int i, int n) {
  if (i == 0) return lo;
  if (i == n) return hi;
  return lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n);
}

std::vector<double> parse_triple(const std::string& text, const std::string& what) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('x', start), text.size());
    double v = 0.0;
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last || !std::isfinite(v))
      throw std::invalid_argument(what + " must be three numbers like 1x0.1x1, got '" + text + "'");
    values.push_back(v);
    start = end + 1;
  }
  if (values.size() != 3)
    throw std::invalid_argument(what + " must be three numbers like 1x0.1x1, got '" + text + "'");
  return values;
}

}  // namespace

TetMesh make_box_mesh(const Vec3& size_m, int nx, int ny, int nz, const std::array<int, 3>& parts) {
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("box cells must be at least 1 in each direction");
  if (parts[0] < 1 || parts[0] > nx || parts[1] < 1 || parts[1] > ny || parts[2] < 1 || parts[2] > nz)
    throw std::invalid_argument(fmt::format("box parts={}x{}x{} must be at least 1 and at most the cells {}x{}x{}",
                                            parts[0], parts[1], parts[2], nx, ny, nz));
  if (!(size_m.minCoeff() > 0.0) || !size_m.allFinite())
    throw std::invalid_argument("box size must be positive and finite");
  const Vec3 hi = size_m / 2.0, lo = -hi;
  std::vector<Vec3> x;
  x.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1));
  const auto index = [&](int i, int j, int k) { return static_cast<std::int32_t>((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        x.emplace_back(grid_coordinate(lo.x(), hi.x(), i, nx), grid_coordinate(lo.y(), hi.y(), j, ny),
                       grid_coordinate(lo.z(), hi.z(), k, nz));

  // The 6 axis orders of the Kuhn subdivision; odd permutations come out
  // negatively oriented, so their last two vertices are swapped.
  static constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  std::vector<Tet> tets;
  tets.reserve(static_cast<std::size_t>(nx) * ny * nz * 6);
  const bool with_parts = parts[0] * parts[1] * parts[2] > 1;
  std::vector<std::int32_t> tet_part;
  const auto block = [](int i, int p, int n) { return static_cast<int>(static_cast<std::int64_t>(i) * p / n); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int p = 0; p < 6; ++p) {
          if (with_parts)
            tet_part.push_back((block(k, parts[2], nz) * parts[1] + block(j, parts[1], ny)) * parts[0] +
                               block(i, parts[0], nx));
          int c[3] = {i, j, k};
          Tet t{};
          t[0] = index(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[kOrders[p][s]];
            t[s + 1] = index(c[0], c[1], c[2]);
          }
          if (p >= 3) std::swap(t[2], t[3]);
          tets.push_back(t);
        }
  TetMesh mesh = build_tet_mesh(std::move(x), std::move(tets));
  mesh.tet_part = std::move(tet_part);
  return mesh;
}

bool is_generator_source(const std::string& source) { return source.rfind("box:", 0) == 0; }

TetMesh make_generated_mesh(const std::string& source) {
  if (!is_generator_source(source)) throw std::invalid_argument("unknown mesh generator '" + source + "'");
  std::vector<double> size, cells, parts;
  const std::string args = source.substr(4);
  std::size_t start = 0;
  while (start < args.size()) {
    const std::size_t end = std::min(args.find(',', start), args.size());
    const std::string item = args.substr(start, end - start);
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    if (key == "size")
      size = parse_triple(value, "box size");
    else if (key == "cells")
      cells = parse_triple(value, "box cells");
    else if (key == "parts")
      parts = parse_triple(value, "box parts");
    else
      throw std::invalid_argument("unknown box parameter '" + key + "' (expected size=..., cells=..., parts=...)");
    start = end + 1;
  }
  if (size.empty()) throw std::invalid_argument("box generator needs size=SXxSYxSZ");
  if (cells.empty()) cells = {1, 1, 1};
  for (double c : cells)
    if (c != std::floor(c) || c < 1 || c > 1000) throw std::invalid_argument("box cells must be whole numbers in 1..1000");
  // 6 tets a cell. Past this the mesh alone takes gigabytes and the run's
  // models several times more: refuse it here, before allocating, rather
  // than die of bad_alloc later (the scaling scene's largest is ~1M tets).
  const double tets = 6.0 * cells[0] * cells[1] * cells[2];
  if (tets > kMaxGeneratedTets)
    throw std::invalid_argument(fmt::format("box cells={}x{}x{} give {:.0f} tets; a generated box has at most {:.0f}",
                                            cells[0], cells[1], cells[2], tets, kMaxGeneratedTets));
  if (parts.empty()) parts = {1, 1, 1};
  for (std::size_t a = 0; a < 3; ++a)
    if (parts[a] != std::floor(parts[a]) || parts[a] < 1 || parts[a] > cells[a])
      throw std::invalid_argument("box parts must be whole numbers from 1 to the cells along each axis");
  return make_box_mesh(Vec3(size[0], size[1], size[2]), static_cast<int>(cells[0]), static_cast<int>(cells[1]),
                       static_cast<int>(cells[2]),
                       {static_cast<int>(parts[0]), static_cast<int>(parts[1]), static_cast<int>(parts[2])});
}

}  // namespace tcb
