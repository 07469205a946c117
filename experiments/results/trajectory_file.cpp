#include "experiments/results/trajectory_file.hpp"

#include <cstring>

#include "sim/io/input_error.hpp"
#include "sim/mesh/curve_numbering.hpp"

namespace tcb {
namespace {

constexpr char kMagic[8] = {'T', 'C', 'B', 'T', 'R', 'J', '0', '1'};

template <class T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
bool get(std::istream& in, T& value) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&value), sizeof(T)));
}

}  // namespace

namespace {

// x, y, z of every vector as float32, in the file's layout.
void to_float_buffer(const std::vector<Vec3>& in, std::vector<float>& buffer) {
  buffer.resize(3 * in.size());
  for (std::size_t i = 0; i < in.size(); ++i)
    for (int k = 0; k < 3; ++k) buffer[3 * i + k] = static_cast<float>(in[i][k]);
}

}  // namespace

void as_float32(const std::vector<Vec3>& in, std::vector<float>& buffer, std::vector<Vec3>& out) {
  to_float_buffer(in, buffer);
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = Vec3(buffer[3 * i], buffer[3 * i + 1], buffer[3 * i + 2]);
}

TrajectoryWriter::TrajectoryWriter(const std::filesystem::path& path, const World& world, int every)
    : m_file(path), m_every(every) {
  std::ostream& out = m_file.stream();
  out.write(kMagic, sizeof kMagic);
  put(out, static_cast<std::uint32_t>(every));
  put(out, static_cast<std::uint32_t>(world.bodies.size()));
  for (const Body& b : world.bodies) {
    put(out, static_cast<std::uint32_t>(b.x_m.size()));
    std::vector<double> masses = b.mass_kg, scratch;
    masses.resize(b.x_m.size(), 0.0);  // passive bodies may carry none
    const std::vector<double>& in_file = in_file_order(*b.mesh, masses, scratch);
    out.write(reinterpret_cast<const char*>(in_file.data()),
              static_cast<std::streamsize>(in_file.size() * sizeof(double)));
  }
}

void TrajectoryWriter::write_step(const World& world) {
  if (m_every <= 0 || world.step_index % m_every != 0) return;
  std::ostream& out = m_file.stream();
  put(out, static_cast<std::int64_t>(world.step_index));
  for (const Body& b : world.bodies) {
    for (const std::vector<Vec3>* field : {&b.x_m, &b.v_m_per_s}) {
      to_float_buffer(in_file_order(*b.mesh, *field, m_file_order), m_scratch);
      out.write(reinterpret_cast<const char*>(m_scratch.data()), static_cast<std::streamsize>(m_scratch.size() * sizeof(float)));
    }
  }
}

TrajectoryReader::TrajectoryReader(const std::filesystem::path& path) : m_path(path), m_in(path, std::ios::binary) {
  if (!m_in) throw InputError(path.string(), 0, "cannot open the trajectory (was the run made with --trajectory?)");
  std::error_code ec;
  m_size = std::filesystem::file_size(path, ec);
  char magic[8] = {};
  std::uint32_t every = 0, bodies = 0;
  if (!m_in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(path.string(), 0, "not a tcbench trajectory (expected TCBTRJ01)");
  if (!get(m_in, every) || !get(m_in, bodies) || every == 0 || every > (1u << 30) || bodies > m_size / 4)
    throw InputError(path.string(), 0, "truncated or invalid trajectory header");
  m_every = static_cast<int>(every);
  for (std::uint32_t b = 0; b < bodies; ++b) {
    std::uint32_t n = 0;
    if (!get(m_in, n) || n > m_size / sizeof(double))  // more masses than the file holds
      throw InputError(path.string(), 0, "truncated or invalid trajectory header");
    std::vector<double> masses(n);
    if (!m_in.read(reinterpret_cast<char*>(masses.data()), static_cast<std::streamsize>(n * sizeof(double))))
      throw InputError(path.string(), 0, "truncated trajectory header");
    m_masses.push_back(std::move(masses));
  }
}

std::optional<TrajectoryFrame> TrajectoryReader::next() {
  TrajectoryFrame frame;
  if (!get(m_in, frame.step)) return std::nullopt;
  for (const auto& masses : m_masses) {
    for (auto* field : {&frame.x_m, &frame.v_m_per_s}) {
      m_scratch.resize(3 * masses.size());
      if (!m_in.read(reinterpret_cast<char*>(m_scratch.data()), static_cast<std::streamsize>(m_scratch.size() * sizeof(float))))
        throw InputError(m_path.string(), 0, "truncated frame at step " + std::to_string(frame.step));
      std::vector<Vec3> values(masses.size());
      for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = Vec3(m_scratch[3 * i], m_scratch[3 * i + 1], m_scratch[3 * i + 2]);
      field->push_back(std::move(values));
    }
  }
  return frame;
}

}  // namespace tcb
