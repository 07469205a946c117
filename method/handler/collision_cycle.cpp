#include "method/handler/collision_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "method/handler/heap_bytes.hpp"
#include "method/handler/work_units.hpp"

namespace tcb {

CollisionCycle::CollisionCycle(const World& world, CollisionSettings settings, DetectionMode mode,
                               CycleSchedule schedule)
    : m_settings(std::move(settings)),
      m_mode(mode),
      m_granularity(schedule.granularity),
      m_order(schedule.order),
      m_widen_stale(schedule.widen_stale),
      m_rehash_stale(schedule.rehash_stale && mode == DetectionMode::SpatialHash),
      m_keep_table(schedule.keep_table && mode == DetectionMode::SpatialHash),
      m_keep_table_rehash_share(schedule.keep_table_rehash_share),
      m_predict_tasks(schedule.predict_tasks),
      m_whole_surface_hash(schedule.whole_surface_hash),
      m_pairs(world),
      m_detector(world, m_settings.detection),
      m_surface(world, m_settings.detection.cell_size_m, m_settings.detection.hash) {
  if (m_rehash_stale || m_keep_table) m_detector.enable_refresh();
  if (m_widen_stale) m_detector.enable_widening();
  if (mode == DetectionMode::SpatialHash) warm_up(world);
  if (m_settings.threads > 1 && mode == DetectionMode::SpatialHash) {
    m_pool = std::make_unique<WorkerPool>(m_settings.threads);
    for (int t = 0; t < m_settings.threads; ++t) m_thread_scratch.push_back(m_detector.make_scratch());
    m_thread_hits.resize(static_cast<std::size_t>(m_settings.threads));
  }
  // [0] serves the serial path; with a pool, one a thread.
  for (int t = 0; t < (m_pool ? m_settings.threads : 1); ++t) m_surface_scratch.push_back(m_surface.make_scratch());
  m_lookup.resize(world.bodies.size());
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    m_lookup[b].assign(world.bodies[b].x_m.size(), -1);
    bool queried = false;
    for (std::size_t o = 0; o < world.bodies.size(); ++o) queried |= m_pairs.enabled(b, o);
    if (!queried) continue;
    for (std::size_t v = 0; v < world.bodies[b].x_m.size(); ++v)
      m_queries.emplace_back(static_cast<std::int32_t>(b), static_cast<std::int32_t>(v));
  }
}

void CollisionCycle::warm_up(const World& world) {
  // Both tables hashed and built once at the initial positions, before any
  // step: their vectors reach their working size and their memory is touched
  // here, not inside the first steps' budgets (measured under fine tasks:
  // the first cycle's hashing steps overran by 200-360 us on sneaker_grass
  // and plates20, later cycles' did not: vectors growing and memory touched
  // for the first time). Every cycle starts its tables afresh, so
  // nothing of this is seen by the results. A state the hash cannot take is
  // left for the first cycle to report.
  try {
    if (m_granularity.fine()) {  // the path the fine tasks take: insert_box() and a build in pieces
      bool done = false;
      m_detector.begin_hash();
      m_detector.hash_some_tets(world, m_pairs, std::numeric_limits<std::size_t>::max(), done);
      m_detector.mutable_hash().build();
    } else {
      m_detector.hash_tets(world, m_pairs, m_pool.get());
    }
    m_surface.begin_epoch();
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
      if (!m_pairs.has_partner(b)) continue;
      for (std::size_t t = 0; t < world.bodies[b].mesh->surface.size(); ++t)
        m_surface.hash_triangle(world, static_cast<std::int32_t>(b), static_cast<std::int32_t>(t));
    }
    m_surface.build();
  } catch (const HashOverflow&) {
  }
}

void CollisionCycle::begin(const World& world) {
  m_tet_margin_m = m_surface_margin_m = m_tet_motion_m = 0.0;  // a new tet hash starts now
  m_refresh_wait = false;
  m_opening_refresh = false;
  m_margin_step = world.step_index;
  for (const Contact& c : m_contacts) m_lookup[c.object][c.vertex] = -1;
  m_contacts.clear();
  m_batch.clear();
  ++m_number;
  m_tasks = 0;
  if (m_order == WorkOrder::FastestFirst) enter(Stage::Prioritize, world);
  else enter_detection(world);
}

void CollisionCycle::enter_detection(const World& world) {
  m_hash_begin_step = world.step_index;
  m_opening_refresh = m_keep_table && m_table_kept &&
                      static_cast<double>(m_detector.overflow_tets()) <=
                          m_keep_table_rehash_share * static_cast<double>(m_detector.tet_count());
  if (m_opening_refresh) {
    // The refresh's tasks, then the queries from the first point (the
    // refresh's completion below).
    enter(Stage::RefreshTets, world);
    m_resume_stage = Stage::QueryPoints;
    m_resume_cursor = 0;
    m_motion_at_refresh_m = m_tet_motion_m;
    m_detector.begin_refresh();
    return;
  }
  enter(m_mode == DetectionMode::SpatialHash ? Stage::HashTets : Stage::QueryPoints, world);
  if (m_stage == Stage::HashTets) {
    m_table_kept = false;  // until this hash completes
    if (m_granularity.fine()) m_detector.begin_hash();
  }
}

bool CollisionCycle::needs_refresh(const World& world) const {
  if (!m_rehash_stale || m_refresh_wait || m_fresh_step == world.step_index) return false;
  // Only before a task that queries the tet table: a point query, or the
  // re-detection that opens a contact's border work.
  if (m_stage == Stage::QueryPoints) return m_cursor < m_queries.size();
  if (m_stage != Stage::BorderDepth || m_cursor >= m_contacts.size() || m_edge != 0) return false;
  const Contact& c = m_contacts[m_cursor];
  return !c.separated && c.detected_step != world.step_index;
}

void CollisionCycle::grow_margins(const World& world) {
  if (!m_widen_stale || world.step_index == m_margin_step) return;
  // One O(vertices) scan a step, while a cycle spans steps (not charged: like
  // the handler's own bookkeeping). A diverged state widens nothing.
  const double fastest = world.max_speed_m_per_s();
  const double moved = std::isfinite(fastest)
                           ? static_cast<double>(world.step_index - m_margin_step) * m_settings.dt_s * fastest
                           : 0.0;
  // Capped at half a cell: a query then covers at most two cells an axis.
  // Uncapped, a cycle slowed by wide queries spans more steps, its margin
  // grows, its queries get wider still (measured on plates20: overshoot p99
  // 590 %). Beyond the cap the bound no longer holds.
  const double cap = 0.5 * m_settings.detection.cell_size_m;
  m_tet_motion_m += moved;
  m_tet_margin_m = std::min(m_tet_motion_m, cap);
  m_surface_margin_m = std::min(m_surface_margin_m + moved, cap);
  m_margin_step = world.step_index;
}

void CollisionCycle::prioritize(const World& world) {
  m_query_order.resize(m_queries.size());
  std::vector<double> speed2(m_queries.size());
  for (std::uint32_t i = 0; i < m_queries.size(); ++i) {
    m_query_order[i] = i;
    const auto [b, v] = m_queries[i];
    const double s2 = world.bodies[b].v_m_per_s[v].squaredNorm();
    speed2[i] = std::isfinite(s2) ? s2 : 0.0;  // a strict weak order even for a diverged vertex
  }
  std::stable_sort(m_query_order.begin(), m_query_order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return speed2[a] > speed2[b]; });
}

void CollisionCycle::restore_index_order() {
  // Contacts back in (body, vertex) order, their lookup with them: the
  // completed cycle looks exactly like one queried in index order.
  std::sort(m_contacts.begin(), m_contacts.end(), [](const Contact& a, const Contact& b) {
    return std::tie(a.object, a.vertex) < std::tie(b.object, b.vertex);
  });
  for (std::size_t i = 0; i < m_contacts.size(); ++i)
    if (m_lookup[m_contacts[i].object][m_contacts[i].vertex] >= 0)
      m_lookup[m_contacts[i].object][m_contacts[i].vertex] = static_cast<std::int32_t>(i);
}

void CollisionCycle::add_contact(const Contact& c) {
  m_lookup[c.object][c.vertex] = static_cast<std::int32_t>(m_contacts.size());
  m_contacts.push_back(c);
}

void CollisionCycle::enter(Stage stage, const World& world) {
  m_stage = stage;
  m_cursor = 0;
  m_batch.clear();  // a batch belongs to the stage that made it
  if (stage == Stage::HashSurface) {
    // The bodies some point is inside, ascending; their triangles are walked
    // by a cursor (m_surface_body, m_cursor), one a task.
    std::vector<char> needed(world.bodies.size(), 0);
    for (const Contact& c : m_contacts) needed[c.other] = 1;
    m_surface_bodies.clear();
    for (std::size_t b = 0; b < world.bodies.size(); ++b)
      if (needed[b] && !world.bodies[b].mesh->surface.empty()) m_surface_bodies.push_back(static_cast<std::int32_t>(b));
    m_surface_body = 0;
    m_surface.begin_epoch();
    m_surface_margin_m = 0.0;  // a new surface hash starts now
  } else if (stage == Stage::BorderDepth) {
    m_edge = 0;
    m_depth_check_step = -1;  // a new contact list: decided afresh
  } else if (stage == Stage::Propagate) {
    m_layer = 0;
    if (m_granularity.fine()) start_layer_scan();  // stage BuildLayer
    else build_next_layer(world);
  }
}

// The next layer: contacts without depth next to a contact of the layer just
// finished (or, for layer 1, next to any border point).
void CollisionCycle::start_layer_scan() {
  ++m_layer;
  ++m_layer_scan;
  m_layer_mark.resize(m_contacts.size(), 0);
  m_layer_items.clear();
  m_scan_cursor = 0;
  m_stage = Stage::BuildLayer;
}

// build_next_layer() in pieces: queues each new neighbour once (marked by
// this scan) in the order met. True when the scan is complete.
bool CollisionCycle::scan_layer_some(const World& world, std::size_t max_contacts) {
  const std::size_t end = std::min(m_contacts.size(), m_scan_cursor + max_contacts);
  for (; m_scan_cursor < end; ++m_scan_cursor) queue_neighbours(world, m_contacts[m_scan_cursor]);
  return m_scan_cursor == m_contacts.size();
}

void CollisionCycle::queue_neighbours(const World& world, const Contact& c) {
  if (c.depth_source == DepthSource::None || c.layer != m_layer - 1) return;
  const auto& adjacency = world.bodies[c.object].mesh->vertex_neighbours;
  for (const std::int32_t* j = adjacency.begin(c.vertex); j != adjacency.end(c.vertex); ++j) {
    const std::int32_t n = m_lookup[c.object][*j];
    if (n < 0 || m_contacts[n].other != c.other || m_contacts[n].depth_source != DepthSource::None ||
        m_layer_mark[n] == m_layer_scan)
      continue;
    m_layer_mark[n] = m_layer_scan;
    m_layer_items.push_back(n);
  }
}

void CollisionCycle::build_next_layer(const World& world) {
  // The paper's granularity: the whole scan in the task that ends a layer,
  // its points in index order. Layer 1 grows from the border points, so
  // every contact is scanned. A later layer grows from the contacts of
  // the layer just finished, and those are among its items: only
  // propagate_depth() sets a layer above 0, and only on a layer's items.
  // So only those items are scanned (the same test, so the same points
  // queued; sorted, the same layer): a layer costs its points, not every
  // contact, which matters where many layers are deep. (On the dog pair
  // little: ms_propagate 0.26-0.39 -> 0.24-0.25 ms, micro_collision_cycle
  // BM_DogPair/0/100/1, alternated binaries; the scan's time there is the
  // sources' neighbours, which both ways visit.)
  const bool first = m_layer == 0;
  m_layer_sources.swap(m_layer_items);
  start_layer_scan();
  if (first) {
    scan_layer_some(world, m_contacts.size());
  } else {
    for (const std::int32_t i : m_layer_sources) queue_neighbours(world, m_contacts[static_cast<std::size_t>(i)]);
  }
  std::sort(m_layer_items.begin(), m_layer_items.end());
  m_stage = Stage::Propagate;
  m_cursor = 0;
}

namespace {

// The reported stage of an internal one (stage_costs.hpp); Idle and Done run no tasks.
CostStage cost_stage(CollisionCycle::Stage stage) {
  using S = CollisionCycle::Stage;
  switch (stage) {
    case S::Prioritize: return CostStage::Prioritize;
    case S::HashTets:
    case S::BuildTetHash:
    case S::RefreshTets:
    case S::BuildOverflow: return CostStage::HashTets;
    case S::QueryPoints: return CostStage::QueryPoints;
    case S::HashSurface:
    case S::BuildSurfaceHash: return CostStage::HashSurface;
    case S::BorderDepth: return CostStage::BorderDepth;
    case S::Propagate:
    case S::BuildLayer: return CostStage::Propagate;
    case S::Forces:
    case S::Idle:
    case S::Done: break;
  }
  return CostStage::Forces;
}

}  // namespace

void CollisionCycle::end_refresh(const World& world) {
  // The motion since the refresh began is what its boxes may miss.
  m_tet_motion_m -= m_motion_at_refresh_m;
  m_tet_margin_m = std::min(m_tet_motion_m, 0.5 * m_settings.detection.cell_size_m);
  if (m_opening_refresh) {
    // keep_table: the refresh stands for the cycle's hash and is dated as
    // the hash would be: by its one task's step, or under fine tasks by the
    // step the cycle's detection began in (a later rehash_stale refresh then
    // covers what moved since; no query task need run between the two).
    m_opening_refresh = false;
    m_fresh_step = m_granularity.fine() ? m_hash_begin_step : world.step_index;
    enter(Stage::QueryPoints, world);
    return;
  }
  // A refresh that spanned steps holds its first tets' older positions; it
  // is not restarted (that could never end): the table counts as this step's.
  m_fresh_step = world.step_index;
  m_stage = m_resume_stage;
  m_cursor = m_resume_cursor;
  m_refresh_wait = true;  // the resumed stage runs a task before the next refresh
}

bool CollisionCycle::advance(World& world, Budget& budget) {
  grow_margins(world);
  if (m_stage == Stage::Done || m_stage == Stage::Idle) return m_stage == Stage::Done;
  // Time goes to a stage when the stage changes: a clock read per change.
  double since_ms = m_clock();
  const auto close_stage = [&](CostStage stage) {
    const double now_ms = m_clock();
    m_step_costs.ms_of(stage) += now_ms - since_ms;
    since_ms = now_ms;
  };
  while (m_stage != Stage::Done && m_stage != Stage::Idle) {
    if (needs_refresh(world)) {  // not a task: the refresh's tasks follow
      m_resume_stage = m_stage;
      m_resume_cursor = m_cursor;
      m_motion_at_refresh_m = m_tet_motion_m;
      m_detector.begin_refresh();
      m_batch.clear();  // answered against the table before the refresh
      m_stage = Stage::RefreshTets;
      close_stage(cost_stage(m_resume_stage));
    }
    std::uint64_t work = 0;
    const CostStage task_stage = cost_stage(m_stage);
    if (m_stage == Stage::QueryPoints || m_stage == Stage::BorderDepth) m_refresh_wait = false;
    switch (m_stage) {
      case Stage::Prioritize:
        prioritize(world);
        work = work::kPrioritize * m_queries.size();
        enter_detection(world);
        break;
      case Stage::HashTets:
        if (!m_granularity.fine()) {
          // Unlimited, this call runs the cycle to its end: every query of
          // the table is made at these positions, so unless they are widened
          // (widen_stale, once a cycle spans steps) the detector may leave
          // out the tets, and cells of tets, no query point can reach (the
          // same answers and work).
          work = m_detector.hash_tets(world, m_pairs, m_pool.get(),
                                      budget.kind() == BudgetKind::None && !(m_tet_margin_m > 0.0));
          m_fresh_step = world.step_index;
          m_table_kept = true;
          ++m_fresh_tet_hashes;
          enter(Stage::QueryPoints, world);
        } else {
          bool hashed = false;
          work = m_detector.hash_some_tets(world, m_pairs, std::max<std::size_t>(1, m_granularity.tets_per_task), hashed);
          if (hashed) {
            m_detector.mutable_hash().begin_build();
            enter(Stage::BuildTetHash, world);
          }
        }
        break;
      case Stage::BuildTetHash:
        if (m_detector.mutable_hash().build_some(std::max<std::size_t>(1, m_granularity.build_visits_per_task))) {
          m_fresh_step = m_hash_begin_step;  // tets hashed in earlier steps are stale: refreshed if so
          m_table_kept = true;
          ++m_fresh_tet_hashes;
          enter(Stage::QueryPoints, world);
        }
        break;
      case Stage::RefreshTets: {
        bool refreshed = true;
        if (m_granularity.fine())
          work = m_detector.refresh_some_tets(world, m_pairs, m_granularity.tets_per_task, refreshed);
        else  // the paper's granularity: one task, on the pool when there is one
          work = m_detector.refresh_tets(world, m_pairs, m_pool.get());
        if (!refreshed) break;
        // At the paper's granularity refresh_tets() has built the overflow
        // already. keep_table's opening refresh stands for HashTets, one
        // task with its table's build; a rehash_stale refresh keeps its
        // BuildOverflow task, which then finds the table built.
        if (m_opening_refresh && !m_granularity.fine()) {
          end_refresh(world);
          break;
        }
        m_detector.mutable_overflow().begin_build();
        m_stage = Stage::BuildOverflow;
        break;
      }
      case Stage::BuildOverflow: {
        const std::size_t per_task =
            m_granularity.fine() ? m_granularity.build_visits_per_task : std::numeric_limits<std::size_t>::max();
        if (m_detector.mutable_overflow().build_some(per_task)) end_refresh(world);
        break;
      }
      case Stage::QueryPoints:
        if (m_cursor < m_queries.size() && m_pool) {
          // The same task as below with its answer computed ahead: the same
          // contact and work, so budgets stop at the same point.
          if (!batch_holds(world)) query_batch(world, budget);
          if (checks_decide_nothing(world, budget)) {
            // The answers before the batch's last are taken here, each still
            // a task charged and counted as the loop's end does (serial:
            // about 12 ns a query through the loop on the dog pair's
            // 2-thread cycle).
            for (const std::size_t last = m_batch_begin + m_batch.size() - 1; m_cursor < last;) {
              const Answer& answer = m_batch[m_cursor++ - m_batch_begin];
              if (answer.part >= 0) add_contact(hit_of(answer));
              count_task(budget, task_stage, answer.work);
            }
          }
          const Answer& answer = m_batch[m_cursor++ - m_batch_begin];
          work = answer.work;
          if (answer.part >= 0) add_contact(hit_of(answer));
        } else if (m_cursor < m_queries.size()) {
          const auto [body, vertex] =
              m_queries[m_order == WorkOrder::FastestFirst ? m_query_order[m_cursor++] : m_cursor++];
          if (const auto hit = detect(world, body, vertex, work)) add_contact(*hit);
        }
        if (m_cursor == m_queries.size()) enter(Stage::HashSurface, world);
        break;
      case Stage::HashSurface:
        if (m_whole_surface_hash && m_surface_body == 0 && m_cursor == 0 && !m_surface_bodies.empty() &&
            (m_pool || budget.kind() == BudgetKind::None)) {
          // The whole stage at once, on the threads or on this one: the same
          // table, charged as the one-triangle tasks below would be, none of
          // which the budget stops. One thread takes it too, for the
          // owners' build (SpatialHash::insert_all_and_build): the serial
          // insert_box() and build() reach across the whole table for
          // every entry (micro_collision_cycle BM_SurfaceWholePaired: the
          // stage 1.19x faster on the dog pair, 1.03x on settled plates20).
          // But only without a budget: under a work budget, whether it fits
          // takes a pass over the triangles first (work_of_all), paid on
          // one thread in every cycle on top of the hash, and no gain of it
          // there has been measured; so one thread keeps the one-triangle
          // tasks under any budget.
          std::optional<WorkerPool> caller;  // made only when needed: a pool is not free to build
          WorkerPool& pool = m_pool ? *m_pool : caller.emplace(1);
          if (surface_fits(world, budget, pool)) {
            m_surface.hash_all(world, m_surface_bodies, pool, m_surface_work);
            ++m_whole_surface_hashes;
            for (std::size_t i = 0; i + 1 < m_surface_work.size(); ++i) count_task(budget, task_stage, m_surface_work[i]);
            work = m_surface_work.back();  // not empty: some body with a surface is listed
            m_surface_body = m_surface_bodies.size();
            enter(Stage::BorderDepth, world);
            break;
          }
        }
        if (m_surface_body < m_surface_bodies.size()) {
          const std::int32_t body = m_surface_bodies[m_surface_body];
          work = m_surface.hash_triangle(world, body, static_cast<std::int32_t>(m_cursor++));
          if (m_cursor == world.bodies[body].mesh->surface.size()) {
            ++m_surface_body;
            m_cursor = 0;
          }
        }
        if (m_surface_body == m_surface_bodies.size()) {
          if (!m_granularity.fine()) {
            m_surface.build();
            enter(Stage::BorderDepth, world);
          } else {
            m_surface.begin_build();
            enter(Stage::BuildSurfaceHash, world);
          }
        }
        break;
      case Stage::BuildSurfaceHash:
        if (m_surface.build_some(std::max<std::size_t>(1, m_granularity.build_visits_per_task))) enter(Stage::BorderDepth, world);
        break;
      case Stage::BorderDepth:
        if (m_cursor < m_contacts.size()) {
          Contact& c = m_contacts[m_cursor];
          if (m_edge == 0) {  // the point's first task
            if (c.detected_step != world.step_index) {  // positions changed since detection
              if (const auto again = detect(world, c.object, c.vertex, work)) {
                c.other = again->other;
                c.tet = again->tet;
                c.barycentric = again->barycentric;
                c.detected_step = again->detected_step;
              } else {
                c.separated = true;
                m_lookup[c.object][c.vertex] = -1;
              }
            }
            m_border_sum = BorderSum{};
          }
          if (c.separated) {
            ++m_cursor;
          } else if (!m_granularity.fine()) {
            if (m_pool && depth_batch_allowed(world)) {
              // The same task with its depth computed ahead (see depth_batch).
              if (!batch_holds(world)) depth_batch(world, budget);
              const Answer& answer = m_batch[m_cursor - m_batch_begin];
              work += answer.work;
              c = hit_of(answer);
            } else {
              work += border_point_depth(world, c, m_contacts, m_lookup, m_surface, m_surface_scratch[0],
                                         m_surface_margin_m);
            }
            c.depth_offset_m = contact_offset_m(world, c);
            c.depth_step = world.step_index;
            ++m_cursor;
          } else {
            // One border edge a task (the edges that are not border edges
            // cost nothing and go with it); the point's depth when its last
            // edge is done.
            if (m_edge == 0) work += work::kBorderPoint;
            const auto& adjacency = world.bodies[c.object].mesh->vertex_neighbours;
            const std::int32_t* q = adjacency.begin(c.vertex) + m_edge;
            for (bool crossed = false; !crossed && q != adjacency.end(c.vertex); ++q, ++m_edge) {
              const std::int32_t qi = m_lookup[c.object][*q];
              if (qi >= 0 && m_contacts[qi].other == c.other) continue;  // not a border edge
              work += border_edge_crossing(world, c, *q, m_contacts, m_lookup, m_surface, m_surface_scratch[0],
                                           m_surface_margin_m,
                                           m_border_sum);
              crossed = true;
            }
            if (q == adjacency.end(c.vertex)) {
              finish_border_depth(c, m_border_sum);
              c.depth_offset_m = contact_offset_m(world, c);
              c.depth_step = world.step_index;
              ++m_cursor;
              m_edge = 0;
            }
          }
        }
        if (m_cursor == m_contacts.size()) enter(Stage::Propagate, world);
        break;
      case Stage::Propagate:
        if (m_cursor < m_layer_items.size()) {
          Contact& c = m_contacts[m_layer_items[m_cursor++]];
          work = propagate_depth(world, c, m_contacts, m_lookup, m_layer);
          c.depth_offset_m = contact_offset_m(world, c);
          c.depth_step = world.step_index;
        }
        if (m_cursor == m_layer_items.size()) {
          if (m_granularity.fine()) {
            start_layer_scan();
            break;
          }
          build_next_layer(world);
          if (m_layer_items.empty()) enter(Stage::Forces, world);
        }
        break;
      case Stage::BuildLayer:
        if (scan_layer_some(world, std::max<std::size_t>(1, m_granularity.layer_scan_per_task))) {
          if (m_layer_items.empty()) {
            enter(Stage::Forces, world);
          } else {
            m_stage = Stage::Propagate;
            m_cursor = 0;
          }
        }
        break;
      case Stage::Forces:
        if (m_cursor < m_contacts.size() && m_pool) {
          // The same task with its force computed ahead (see forces_batch).
          if (!batch_holds(world)) forces_batch(world, budget);
          if (checks_decide_nothing(world, budget))  // as the queries' (above)
            for (const std::size_t last = m_batch_begin + m_batch.size() - 1; m_cursor < last; ++m_cursor) {
              m_contacts[m_cursor].force_n = m_batch_forces[m_cursor - m_batch_begin];
              count_task(budget, task_stage, work::kForce);
            }
          m_contacts[m_cursor].force_n = m_batch_forces[m_cursor - m_batch_begin];
          ++m_cursor;
          work = work::kForce;
        } else if (m_cursor < m_contacts.size()) {
          Contact& c = m_contacts[m_cursor++];
          c.force_n = penalty_force(world, c, m_settings.response(c.object, c.other), m_settings.dt_s);
          work = work::kForce;
        }
        if (m_cursor == m_contacts.size()) {
          if (m_order == WorkOrder::FastestFirst) restore_index_order();
          m_stage = Stage::Done;
        }
        break;
      case Stage::Idle:
      case Stage::Done:
        break;
    }
    count_task(budget, task_stage, work);
    if (m_stage == Stage::Done || cost_stage(m_stage) != task_stage) close_stage(task_stage);
    if (m_stage == Stage::Done) break;
    bool stop = budget.expired();  // an interruption point
    if (m_predict_tasks && budget.kind() == BudgetKind::WallMs) {
      // The first poll's gap also holds the handler's work before the cycle
      // (begin(), the margins' scan): not a task's time.
      if (budget.polls() > 1) {
        double& recent = m_task_ms[static_cast<std::size_t>(task_stage)];
        recent = recent == 0.0 ? budget.last_poll_gap_ms() : 0.8 * recent + 0.2 * budget.last_poll_gap_ms();
      }
      stop = stop || budget.would_overrun(m_task_ms[static_cast<std::size_t>(cost_stage(m_stage))]);
    }
    if (stop) {
      close_stage(cost_stage(m_stage));
      m_step_costs.interrupted = static_cast<int>(cost_stage(m_stage));
      return false;
    }
  }
  return m_stage == Stage::Done;
}

bool CollisionCycle::surface_fits(const World& world, const Budget& budget, WorkerPool& pool) const {
  // Unlimited: it fits. A work budget: when the stage's work leaves the
  // budget unspent, so no poll among its tasks (nor the build's, under fine
  // tasks) would stop it; each triangle costs at least a unit, so with no
  // more units left than triangles it cannot, and nothing is summed. A wall
  // budget: which task it stops at is not known ahead, so one a task.
  if (budget.kind() == BudgetKind::None) return true;
  if (budget.kind() != BudgetKind::Work) return false;
  const double left = budget.limit() - static_cast<double>(budget.spent());
  if (left <= static_cast<double>(SurfaceHash::triangle_count(world, m_surface_bodies))) return false;
  return m_surface.work_of_all(world, m_surface_bodies, pool) < left;
}

bool CollisionCycle::batch_holds(const World& world) const {
  return m_batch_step == world.step_index && m_cursor >= m_batch_begin && m_cursor < m_batch_begin + m_batch.size();
}

std::size_t CollisionCycle::batch_size(std::size_t remaining, const Budget& budget) const {
  // Without a budget every remaining task at once; under one, a few dozen
  // a thread, so a batch (all of it charged to the task that starts it)
  // stays short. Answers past where the budget stops are dropped: the next
  // step asks again at its own positions.
  constexpr std::size_t kPerThread = 64;
  const auto threads = static_cast<std::size_t>(m_pool->threads());
  if (budget.kind() == BudgetKind::None) return remaining;
  std::size_t size = kPerThread * threads;
  if (budget.kind() == BudgetKind::Work) {
    // Every query, border-depth and force task charges at least one unit,
    // so no more tasks than units left run before the budget expires (and
    // one when none are left: a step always runs a task). Answers beyond
    // that would be dropped unread.
    const double left = std::ceil(budget.limit() - static_cast<double>(budget.spent()));
    size = left >= 1.0 ? static_cast<std::size_t>(std::min(left, static_cast<double>(size))) : 1;
  } else if (budget.kind() == BudgetKind::WallMs) {
    // The whole batch falls in one task, between two polls: sized to the
    // time left at what this stage's recent batches took per item (a few a
    // thread until one was measured), so the task ends near the limit
    // instead of a 64-a-thread batch past it (measured on plates20 at 6 ms,
    // 2 threads: overshoot p99 13.6-14.0 % with fixed batches, 8.6-8.8 % on
    // one thread).
    size = wall_batch_items(budget.limit() - budget.elapsed_ms(),
                            m_batch_item_ms[static_cast<std::size_t>(cost_stage(m_stage))], threads, size);
  }
  return std::min(remaining, size);
}

std::size_t wall_batch_items(double left_ms, double item_ms, std::size_t threads, std::size_t most) {
  if (!(item_ms > 0.0)) return std::min(4 * threads, most);  // nothing measured yet
  const double fits = std::floor(std::max(left_ms, 0.0) / item_ms);
  return std::clamp(static_cast<std::size_t>(std::min(fits, static_cast<double>(most))), std::min(threads, most), most);
}

std::size_t batch_chunk(std::size_t size, std::size_t threads, std::size_t max_chunk) {
  // Chunks are taken as threads come free: a batch's costly items (colliding
  // points, deep contacts) cluster, and static halves left one thread idle.
  // A small chunk evens the threads' loads, but each chunk costs an atomic
  // increment whose cache line crosses between the cores (and, likely, the
  // threads then work side by side on neighbouring items, each reading lines
  // the other has just read). At 16 items a chunk, the dog pair's 15,460
  // point queries (967 chunks) took 1.20-1.36 ms on 2 threads against
  // 1.07-1.27 ms with this rule (micro_collision_cycle BM_ThreadsPaired/0/0,
  // ms2_query_points, three rounds of alternated binaries). Its 1,541
  // border depths cost about a microsecond each and keep 16: at 256 (7
  // chunks) the 2 threads took longer than one. A quarter of a thread's
  // share, so a budget's batch of 64 items a thread still splits into
  // 16-item chunks.
  constexpr std::size_t kLeast = 16, kChunksPerThread = 4;
  const std::size_t even = size / (kChunksPerThread * std::max<std::size_t>(threads, 1));
  return std::max<std::size_t>(std::min(std::max(even, kLeast), max_chunk), 1);
}

void CollisionCycle::run_batch(std::size_t remaining, std::size_t max_chunk, const World& world,
                               const Budget& budget, const WorkerPool::RangeFunction& f) {
  const std::size_t size = batch_size(remaining, budget);
  m_batch.assign(size, Answer{});
  for (ThreadHits& t : m_thread_hits) t.hits.clear();
  m_batch_begin = m_cursor;
  m_batch_step = world.step_index;
  const bool timed = budget.kind() == BudgetKind::WallMs;
  const double start_ms = timed ? m_clock() : 0.0;
  m_pool->for_chunks(size, batch_chunk(size, static_cast<std::size_t>(m_pool->threads()), max_chunk), f);
  if (!timed || size == 0) return;
  const double item_ms = (m_clock() - start_ms) / static_cast<double>(size);
  double& recent = m_batch_item_ms[static_cast<std::size_t>(cost_stage(m_stage))];
  recent = recent == 0.0 ? item_ms : 0.7 * recent + 0.3 * item_ms;
}

bool CollisionCycle::depth_batch_allowed(const World& world) {
  // A border depth reads the other contacts' `other`, which only the
  // re-detection opening a later point's task changes (or separates). When
  // every point from the cursor on was detected at this step's positions,
  // none is re-detected, and each depth depends on nothing its predecessors
  // write: the depths may be computed ahead. Decided once a step (within a
  // step, only the tasks themselves change the contacts from the cursor on).
  if (m_depth_check_step != world.step_index) {
    m_depth_check_step = world.step_index;
    m_depth_batchable = std::all_of(m_contacts.begin() + static_cast<std::ptrdiff_t>(m_cursor), m_contacts.end(),
                                    [&](const Contact& c) { return c.detected_step == world.step_index; });
  }
  return m_depth_batchable;
}

void CollisionCycle::depth_batch(const World& world, const Budget& budget) {
  const auto depths = [&](int part, std::size_t begin, std::size_t end) {
    SurfaceHash::QueryScratch& scratch = m_surface_scratch[static_cast<std::size_t>(part)];
    for (std::size_t i = begin; i < end; ++i) {
      Contact c = m_contacts[m_batch_begin + i];
      m_batch[i].work =
          border_point_depth(world, c, m_contacts, m_lookup, m_surface, scratch, m_surface_margin_m);
      keep_hit(m_batch[i], part, c);
    }
  };
  run_batch(m_contacts.size() - m_cursor, kDepthChunk, world, budget, depths);
}

void CollisionCycle::forces_batch(const World& world, const Budget& budget) {
  // A penalty force reads its own contact and the world only. Every force
  // task charges work::kForce, so the answers' work is left unread.
  m_batch_forces.resize(m_contacts.size() - m_cursor);
  const auto forces = [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Contact& c = m_contacts[m_batch_begin + i];
      m_batch_forces[i] = penalty_force(world, c, m_settings.response(c.object, c.other), m_settings.dt_s);
    }
  };
  run_batch(m_contacts.size() - m_cursor, kForceChunk, world, budget, forces);
}

bool CollisionCycle::checks_decide_nothing(const World& world, const Budget& budget) const {
  // Without a budget no task ends the step, and no refresh is due before the
  // next (needs_refresh), so the loop's checks between tasks decide nothing.
  return budget.kind() == BudgetKind::None && !(m_rehash_stale && m_fresh_step != world.step_index);
}

void CollisionCycle::query_batch(const World& world, const Budget& budget) {
  const auto queries = [&](int part, std::size_t begin, std::size_t end) {
    TetHashDetector::QueryScratch& scratch = m_thread_scratch[static_cast<std::size_t>(part)];
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t at = m_batch_begin + i;
      const auto [body, vertex] = m_queries[m_order == WorkOrder::FastestFirst ? m_query_order[at] : at];
      const auto hit = m_detector.query_point(world, m_pairs, body, vertex, m_batch[i].work, m_tet_margin_m, scratch);
      if (hit) keep_hit(m_batch[i], part, *hit);
    }
  };
  run_batch(m_queries.size() - m_cursor, kQueryChunk, world, budget, queries);
}

std::optional<Contact> CollisionCycle::detect(const World& world, std::int32_t body, std::int32_t vertex,
                                              std::uint64_t& work) {
  return m_mode == DetectionMode::SpatialHash
             ? m_detector.query_point(world, m_pairs, body, vertex, work, m_tet_margin_m)
             : brute_force_query_point(world, m_pairs, body, vertex, work);
}

std::size_t CollisionCycle::memory_bytes() const {
  std::size_t bytes = m_detector.memory_bytes() + m_surface.memory_bytes() + heap_bytes(m_query_order) +
                      heap_bytes(m_queries) + heap_bytes(m_surface_bodies) + heap_bytes(m_layer_items) +
                      heap_bytes(m_layer_sources) + heap_bytes(m_layer_mark) + heap_bytes(m_contacts) +
                      heap_bytes(m_lookup) + heap_bytes(m_batch) + heap_bytes(m_batch_forces) +
                      heap_bytes(m_thread_scratch) + heap_bytes(m_thread_hits) + heap_bytes(m_surface_scratch) +
                      heap_bytes(m_surface_work);
  for (const auto& s : m_thread_scratch) bytes += heap_bytes(s.tested);
  for (const auto& t : m_thread_hits) bytes += heap_bytes(t.hits);
  for (const auto& s : m_surface_scratch) bytes += heap_bytes(s.seen);
  return bytes;
}

std::size_t CollisionCycle::queries_done() const {
  if (m_stage == Stage::RefreshTets || m_stage == Stage::BuildOverflow)
    return m_resume_stage == Stage::QueryPoints ? m_resume_cursor : m_queries.size();
  if (m_stage == Stage::Idle || m_stage == Stage::Prioritize || m_stage == Stage::HashTets ||
      m_stage == Stage::BuildTetHash)
    return 0;
  return m_stage == Stage::QueryPoints ? m_cursor : m_queries.size();
}

std::size_t CollisionCycle::forces_computed() const {
  if (m_stage == Stage::Done) return m_contacts.size();
  return m_stage == Stage::Forces ? m_cursor : 0;
}

std::int64_t CollisionCycle::depth_fallback() const {
  return std::count_if(m_contacts.begin(), m_contacts.end(),
                       [](const Contact& c) { return c.depth_source == DepthSource::None && !c.separated; });
}

}  // namespace tcb
