#include "experiments/view/live_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "sim/io/atomic_file.hpp"

namespace tcb {
namespace {

using Json = nlohmann::json;

double wall_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Frames for the page: at most about 30 a second, whatever the loop's rate.
constexpr double kFrameIntervalS = 1.0 / 30.0;

}  // namespace

ProbeMessage parse_probe_message(const std::string& body) {
  const Json message = Json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) return {std::nullopt, "not JSON: expected {\"x\": m, \"y\": m, \"z\": m}"};
  if (!message.is_object()) return {std::nullopt, "expected a JSON object {\"x\": m, \"y\": m, \"z\": m}"};
  Vec3 p;
  const char* names[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    const auto it = message.find(names[k]);
    if (it == message.end() || !it->is_number())
      return {std::nullopt, fmt::format("'{}' is missing or not a number", names[k])};
    p[k] = it->get<double>();
    if (!std::isfinite(p[k])) return {std::nullopt, fmt::format("'{}' is not finite", names[k])};
  }
  if (message.size() != 3) return {std::nullopt, "unexpected keys: only x, y and z are allowed"};
  return {p, ""};
}

std::string live_scene_json(const World& world, std::size_t probe_body, double dt_s) {
  Json bodies = Json::array();
  std::vector<std::uint32_t> triangles, surface_body;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const TetMesh& mesh = *world.bodies[b].mesh;
    const auto first = static_cast<std::uint32_t>(surface_body.size());
    std::vector<std::int64_t> index(mesh.vertex_count(), -1);
    for (const std::int32_t v : mesh.surface_vertices) {
      index[static_cast<std::size_t>(v)] = static_cast<std::int64_t>(surface_body.size());
      surface_body.push_back(static_cast<std::uint32_t>(b));
    }
    for (const Triangle& t : mesh.surface)
      for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<std::uint32_t>(index[static_cast<std::size_t>(t[k])]));
    bodies.push_back({{"name", world.bodies[b].name}, {"surface_vertices", {first, surface_body.size() - first}}});
  }
  return Json{{"schema", "tcbench.live/1"},
              {"bodies", bodies},
              {"probe", probe_body},
              {"dt_s", dt_s},
              {"triangles", triangles},
              {"surface_body", surface_body}}
      .dump();
}

LiveSession::LiveSession(const World& world, std::size_t probe_body, double dt_s, double budget_ms)
    : m_probe(probe_body), m_dt_s(dt_s), m_budget_ms(budget_ms) {
  const Body& probe = world.bodies.at(probe_body);
  m_start_m = m_target_m = probe.trajectory->at(world.time_s);
  m_hold = std::make_shared<Trajectory>(Trajectory{{world.time_s}, {m_start_m}});
  // The mouse may take the probe anywhere within a few scene sizes of its start.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Body& b : world.bodies)
    for (const Vec3& x : b.x_m) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  m_reach_m = std::max(2.0 * (hi - lo).norm(), 1e-3);
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    for (const std::int32_t v : world.bodies[b].mesh->surface_vertices) {
      m_surface_body.push_back(static_cast<std::uint32_t>(b));
      m_surface_vertex.push_back(static_cast<std::uint32_t>(v));
    }
  m_scene = live_scene_json(world, probe_body, dt_s);
}

bool LiveSession::set_target(const Vec3& target_m) {
  std::lock_guard lock(m_mutex);
  if ((target_m - m_start_m).norm() > m_reach_m) return false;
  m_target_m = target_m;
  return true;
}

Vec3 LiveSession::target() const {
  std::lock_guard lock(m_mutex);
  return m_target_m;
}

void LiveSession::drive(World& world) {
  const Vec3 target = this->target();
  // The probe holds at the target over the coming step (World::step moves it
  // to trajectory->at(t + dt)): one sample, rewritten in place every step, no
  // allocation in the loop. The saved path is the same samples.
  m_hold->time_s[0] = world.time_s + m_dt_s;
  m_hold->position_m[0] = target;
  world.bodies[m_probe].trajectory = m_hold;
  std::lock_guard lock(m_mutex);
  m_path_time_s.push_back(world.time_s + m_dt_s);
  m_path_m.push_back(target);
}

bool LiveSession::after_step(const StepContext& ctx) {
  const double now = wall_s();
  double sleep_s = 0.0;
  {
    std::lock_guard lock(m_mutex);
    if (m_wall_start_s < 0) m_wall_start_s = now - ctx.world.time_s;
    ++m_steps;
    m_step_wall_s.push_back(now);
    const auto old = std::find_if(m_step_wall_s.begin(), m_step_wall_s.end(), [&](double t) { return t >= now - 1.0; });
    m_step_wall_s.erase(m_step_wall_s.begin(), old);
    if (m_budget_ms > 0 && ctx.handling_ms > m_budget_ms) {
      ++m_over_budget_steps;
      m_overshoots.emplace_back(now, ctx.handling_ms - m_budget_ms);
    }
    const auto stale = std::find_if(m_overshoots.begin(), m_overshoots.end(), [&](const auto& o) { return o.first >= now - 1.0; });
    m_overshoots.erase(m_overshoots.begin(), stale);
    m_overshoot_max_ms = 0.0;
    for (const auto& o : m_overshoots) m_overshoot_max_ms = std::max(m_overshoot_max_ms, o.second);
    if (m_last_frame_s < 0 || now - m_last_frame_s >= kFrameIntervalS) {
      m_last_frame_s = now;
      m_frame = frame_json(ctx);
      ++m_sequence;
      m_changed.notify_all();
    }
    // Real time: simulated time may not run ahead of the wall clock (a slower
    // loop simply falls behind, and its rate says so).
    sleep_s = m_wall_start_s + ctx.world.time_s - now;
    if (m_stopped) return false;
  }
  if (sleep_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(std::min(sleep_s, 0.1)));
  return !stopped();
}

std::string LiveSession::frame_json(const StepContext& ctx) const {
  const World& world = ctx.world;
  std::vector<float> positions;
  positions.reserve(3 * m_surface_body.size());
  for (std::size_t i = 0; i < m_surface_body.size(); ++i) {
    const Vec3& x = world.bodies[m_surface_body[i]].x_m[m_surface_vertex[i]];
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(x[k]));
  }
  // How each point's force was made this step (ForceSource; 255: none), as the replay records it.
  std::map<std::pair<std::int32_t, std::int32_t>, int> source;
  for (const ForcePoint& f : ctx.report.force_points) source[{f.object, f.vertex}] = static_cast<int>(f.source);
  Json contacts = Json::array();
  for (const Contact& c : ctx.handler.contacts()) {
    const auto made = source.find({c.object, c.vertex});
    const Vec3& x = world.bodies[static_cast<std::size_t>(c.object)].x_m[static_cast<std::size_t>(c.vertex)];
    const double depth = c.depth_source == DepthSource::None ? 0.0 : c.depth_m;
    contacts.push_back({static_cast<float>(x.x()), static_cast<float>(x.y()), static_cast<float>(x.z()),
                        static_cast<float>(depth), static_cast<float>(c.direction.x()),
                        static_cast<float>(c.direction.y()), static_cast<float>(c.direction.z()),
                        made == source.end() ? 255 : made->second});
  }
  const std::optional<Vec3> force = world.driven_contact_force_n();
  Vec3 centre = Vec3::Zero();
  for (const Vec3& x : world.bodies[m_probe].x_m) centre += x;
  centre /= static_cast<double>(std::max<std::size_t>(world.bodies[m_probe].x_m.size(), 1));
  const Vec3 f = force.value_or(Vec3::Zero());
  return Json{{"step", ctx.step},
              {"time_s", world.time_s},
              {"positions", positions},
              {"contacts", contacts},
              {"probe_centre_m", {centre.x(), centre.y(), centre.z()}},
              {"probe_target_m", {m_target_m.x(), m_target_m.y(), m_target_m.z()}},
              {"probe_force_n", {f.x(), f.y(), f.z()}},
              {"handling_ms", ctx.handling_ms},
              {"budget_ms", m_budget_ms > 0 ? Json(m_budget_ms) : Json(nullptr)},
              {"rate_hz", static_cast<double>(m_step_wall_s.size())},
              {"target_rate_hz", 1.0 / m_dt_s},
              {"overshoot_max_ms", m_overshoot_max_ms},
              {"over_budget_share", m_steps ? static_cast<double>(m_over_budget_steps) / static_cast<double>(m_steps) : 0.0}}
      .dump();
}

std::optional<std::pair<std::uint64_t, std::string>> LiveSession::next_frame(std::uint64_t seen, double timeout_s) {
  std::unique_lock lock(m_mutex);
  m_changed.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return m_stopped || m_sequence > seen; });
  if (m_stopped || m_sequence <= seen) return std::nullopt;
  return std::make_pair(m_sequence, m_frame);
}

void LiveSession::stop() {
  std::lock_guard lock(m_mutex);
  m_stopped = true;
  m_changed.notify_all();
}

bool LiveSession::stopped() const {
  std::lock_guard lock(m_mutex);
  return m_stopped;
}

void LiveSession::save_path(const std::filesystem::path& path) const {
  std::lock_guard lock(m_mutex);
  std::string text = "time_s,x_m,y_m,z_m\n";
  // The start, so a replay begins where the live session did.
  text += fmt::format("0,{},{},{}\n", m_start_m.x(), m_start_m.y(), m_start_m.z());
  for (std::size_t i = 0; i < m_path_m.size(); ++i)
    text += fmt::format("{},{},{},{}\n", m_path_time_s[i], m_path_m[i].x(), m_path_m[i].y(), m_path_m[i].z());
  write_file_atomically(path, text);
}

}  // namespace tcb
