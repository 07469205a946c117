// The collision cycle's task granularity: the fine tasks (resumable tet
// hashing, builds and layer scans in pieces) find exactly what the paper's one
// hashing task finds when positions do not change, for every piece size, and
// a ticking clock interrupts the hashing and resumes it.
#include "method/handler/collision_cycle.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <set>
#include <tuple>

#include "tests/method/test_worlds.hpp"

using namespace tcb;
using test::Placed;

namespace {

// Every field a contact's force depends on.
using Found = std::vector<std::tuple<int, int, int, int, int, double, double, double, double>>;

Found found(const CollisionCycle& cycle) {
  Found out;
  for (const Contact& c : cycle.contacts())
    out.emplace_back(c.object, c.vertex, c.other, c.tet, static_cast<int>(c.depth_source), c.depth_m,
                     c.direction.x(), c.direction.y(), c.direction.z());
  std::sort(out.begin(), out.end());
  return out;
}

// Every field of every contact, in list order.
bool same_contacts(const std::vector<Contact>& a, const std::vector<Contact>& b) {
  const auto key = [](const Contact& c) {
    return std::make_tuple(c.object, c.vertex, c.other, c.tet, c.barycentric, static_cast<int>(c.depth_source), c.layer,
                           c.detected_step, c.depth_step, c.separated, c.depth_m, c.direction.x(), c.direction.y(),
                           c.direction.z(), c.depth_offset_m.x(), c.depth_offset_m.y(), c.depth_offset_m.z(),
                           c.force_n.x(), c.force_n.y(), c.force_n.z());
  };
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [&](const Contact& x, const Contact& y) { return key(x) == key(y); });
}

// The scene's settings on `threads` threads, every contact damped and with
// friction, so a penalty force reads the bodies' velocities too.
CollisionSettings damped_settings(const World& w, const test::TestScene& scene, int threads) {
  CollisionSettings settings = test::settings_of(w, scene);
  settings.threads = threads;
  for (ResponseParams& r : settings.pair_response) {
    r.damping_n_s_per_m = 20.0;
    r.friction = 0.3;
  }
  return settings;
}

// The next step: the last body moved by `shift_m`, at a velocity growing with
// `speed_up`, so a force computed at an earlier step's state would differ.
void step_last_body(World& w, const Vec3& shift_m, double speed_up) {
  for (Vec3& x : w.bodies.back().x_m) x += shift_m;
  for (Vec3& v : w.bodies.back().v_m_per_s) v = speed_up * Vec3(0.5, -0.3, 0.2);
  ++w.step_index;
}

struct SingleTasks {
  Found found;
  int calls = 0;
  std::uint64_t max_border_task_work = 0;  // the largest task of stage BorderDepth
};

// A whole cycle at fixed positions, one task a call (a work budget of 0
// expires after every task).
SingleTasks cycle_in_single_tasks(const test::TestScene& scene, DetectionMode mode, TaskGranularity granularity) {
  World w = build_world(scene);  // never stepped: positions stay fixed
  CollisionCycle cycle(w, test::settings_of(w, scene), mode, {.granularity = granularity});
  cycle.begin(w);
  SingleTasks out;
  for (bool done = false; !done; ++out.calls) {
    Budget zero = Budget::work_units(0);
    const bool border = cycle.stage() == CollisionCycle::Stage::BorderDepth;
    done = cycle.advance(w, zero);
    if (border) out.max_border_task_work = std::max(out.max_border_task_work, zero.max_task_work());
    REQUIRE(out.calls < 10000000);
  }
  out.found = found(cycle);
  return out;
}


}  // namespace

TEST_CASE("fine tasks find exactly the paper's contacts and depths, and brute force's points, for every piece size",
          "[cycle][granularity]") {
  std::uint64_t paper_border_max = 0, fine_border_max = 0;
  for (const auto& [name, scene] : test::collision_scenes()) {
    INFO(name);
    const SingleTasks paper = cycle_in_single_tasks(scene, DetectionMode::SpatialHash, {});
    const SingleTasks brute = cycle_in_single_tasks(scene, DetectionMode::BruteForce, {});
    REQUIRE(!paper.found.empty());
    CHECK(paper.found == brute.found);
    for (const std::size_t tets : {std::size_t{1}, std::size_t{3}, std::size_t{16}, std::size_t{1} << 30})
      for (const std::size_t visits : {std::size_t{1}, std::size_t{5}, std::size_t{2048}})
        for (const std::size_t scan : {std::size_t{1}, std::size_t{7}, std::size_t{1} << 30}) {
          INFO("tets " << tets << ", visits " << visits << ", scan " << scan);
          const SingleTasks fine = cycle_in_single_tasks(scene, DetectionMode::SpatialHash, {tets, visits, scan});
          CHECK(fine.found == paper.found);
          if (tets == 1) CHECK(fine.calls > paper.calls);  // the hashing really was split
          // One border edge a task: never more than a whole point's work, and
          // less wherever a point has several border edges.
          CHECK(fine.max_border_task_work <= paper.max_border_task_work);
          paper_border_max = std::max(paper_border_max, paper.max_border_task_work);
          fine_border_max = std::max(fine_border_max, fine.max_border_task_work);
        }
  }
  CHECK(fine_border_max < paper_border_max);  // the border work really was split
}

TEST_CASE("the paper's layers, each grown from the last layer's points, are a scan of every contact's layers",
          "[cycle][granularity]") {
  // A fine cube three quarters inside a coarse one: its points inside lie
  // up to six cells from the border, so depths propagate over several
  // layers. The paper's granularity scans only the last layer's points for
  // the next layer; a fine layer scan (BuildLayer) tests every contact, in
  // pieces of one or all. Every field of every contact, the layer too, must
  // agree, whether the cycle runs in one call or one task a call (each
  // layer then built in a call of its own, after the last one's tasks).
  const test::TestScene scene = test::scene_of({{"coarse", "box:size=0.4x0.4x0.4,cells=4x4x4"},
                                                {"fine", "box:size=0.2x0.2x0.2,cells=8x8x8", Vec3(0.15, 0.0, 0.0)}});
  const auto contacts_of = [&](TaskGranularity granularity, bool one_task_a_call) {
    World w = build_world(scene);  // never stepped: positions stay fixed
    CollisionCycle cycle(w, test::settings_of(w, scene), DetectionMode::SpatialHash, {.granularity = granularity});
    cycle.begin(w);
    int calls = 0;
    for (bool done = false; !done; ++calls) {
      Budget budget = one_task_a_call ? Budget::work_units(0) : Budget::unlimited();
      done = cycle.advance(w, budget);
      REQUIRE(calls < 1000000);
    }
    CHECK((calls > 1) == one_task_a_call);
    return cycle.contacts();
  };
  const std::vector<Contact> paper = contacts_of({}, false);
  std::int32_t deepest = 0;
  for (const Contact& c : paper) deepest = std::max(deepest, c.layer);
  REQUIRE(deepest >= 4);  // layers past the first, grown from a layer's points alone
  CHECK(same_contacts(contacts_of({}, true), paper));
  for (const std::size_t scan : {std::size_t{1}, std::size_t{1} << 30})
    for (const bool one_task_a_call : {false, true}) {
      INFO("scan " << scan << ", one task a call " << one_task_a_call);
      CHECK(same_contacts(contacts_of({std::size_t{1} << 30, 2048, scan}, one_task_a_call), paper));
    }
}

TEST_CASE("threads change neither contacts, depths nor any task's work, one task a call or all at once",
          "[cycle][threads]") {
  // With collision.threads > 1 the queries, the paper's border depths and
  // the forces are computed ahead in batches (64 a thread under a work
  // budget, sized by the time left under a wall budget, everything without
  // one) and taken one a task: every task's work and stage, and every field
  // of every contact in list order, must be one thread's.
  std::size_t pushed = 0;  // contacts with a force, one thread, all scenes: so force batches were used
  for (const auto& [name, scene] : test::collision_scenes()) {
    INFO(name);
    using Trace = std::vector<std::pair<int, std::uint64_t>>;  // per task: stage, work
    Trace serial_trace;
    Found serial_single, serial_whole;
    std::vector<Contact> serial_contacts;
    // The unlimited cycle's tasks, units spent, largest task and work a
    // stage: on threads its batch's answers are taken in one loop (no
    // budget, so nothing stops between them), each still a task of its own.
    using Tally = std::tuple<std::int64_t, std::uint64_t, std::uint64_t, std::array<std::uint64_t, kCostStages>>;
    Tally serial_tally;
    std::vector<Contact> serial_whole_contacts;
    for (const int threads : {1, 2, 3}) {
      INFO("threads " << threads);
      World w = build_world(scene);  // never stepped: every contact is detected at this step's positions
      CollisionSettings settings = test::settings_of(w, scene);
      settings.threads = threads;
      CollisionCycle cycle(w, settings);
      cycle.begin(w);
      cycle.start_step_costs();
      Trace trace;
      for (bool done = false; !done;) {
        Budget zero = Budget::work_units(0);
        const int stage = static_cast<int>(cycle.stage());
        done = cycle.advance(w, zero);
        trace.emplace_back(stage, zero.max_task_work());
        REQUIRE(trace.size() < 10000000);
      }
      CollisionCycle whole(w, settings);
      whole.begin(w);
      whole.start_step_costs();
      Budget unlimited = Budget::unlimited();
      REQUIRE(whole.advance(w, unlimited));
      const Tally tally{whole.tasks_done(), unlimited.spent(), unlimited.max_task_work(), whole.step_costs().work};
      // Without a budget the surface hash ran as a whole, on one thread too;
      // one task a call never affords it. Each stage's work is the same
      // either way: the whole hash charges each triangle as its task would.
      CHECK(whole.whole_surface_hashes() == 1);
      CHECK(cycle.whole_surface_hashes() == 0);
      CHECK(whole.step_costs().work == cycle.step_costs().work);
      if (threads == 1) {
        serial_contacts = cycle.contacts();
        serial_trace = trace;
        serial_single = found(cycle);
        // The unlimited reference: one thread, the surface one triangle a
        // task (whole_surface_hash off), as every thread count's whole
        // cycle, this one's included, must match it.
        CycleSchedule one_by_one;
        one_by_one.whole_surface_hash = false;
        CollisionCycle reference(w, settings, DetectionMode::SpatialHash, one_by_one);
        reference.begin(w);
        reference.start_step_costs();
        Budget reference_budget = Budget::unlimited();
        REQUIRE(reference.advance(w, reference_budget));
        CHECK(reference.whole_surface_hashes() == 0);
        serial_whole = found(reference);
        serial_tally = Tally{reference.tasks_done(), reference_budget.spent(), reference_budget.max_task_work(),
                             reference.step_costs().work};
        serial_whole_contacts = reference.contacts();
        REQUIRE(!serial_single.empty());
        CHECK(serial_single == serial_whole);
        CHECK(std::count_if(serial_single.begin(), serial_single.end(), [](const auto& f) {
                return std::get<4>(f) == static_cast<int>(DepthSource::Border);
              }) > 0);  // border depths were computed, so their batches were used
        for (const Contact& c : serial_contacts) pushed += c.force_n != Vec3::Zero();
      } else {
        CHECK(trace == serial_trace);
        CHECK(same_contacts(cycle.contacts(), serial_contacts));
        CHECK(found(cycle) == serial_single);
      }
      CHECK(found(whole) == serial_whole);
      CHECK(tally == serial_tally);
      CHECK(same_contacts(whole.contacts(), serial_whole_contacts));  // in list order
      if (threads > 1) {
        // Under a wall budget (a clock ticking 1 ms a reading, 5 ms a call)
        // batches are sized by time, so where calls stop differs; at fixed
        // positions the contacts may not.
        double now = 0.0;
        const ClockMs clock = [&now] { return now += 1.0; };
        CollisionCycle timed(w, settings);
        timed.set_clock(clock);
        timed.begin(w);
        int calls = 0;
        for (bool done = false; !done; ++calls) {
          Budget b = Budget::wall_ms(5.0, clock);
          done = timed.advance(w, b);
          REQUIRE(calls < 1000000);
        }
        CHECK(calls > 1);
        CHECK(found(timed) == serial_single);
        CHECK(same_contacts(timed.contacts(), serial_contacts));  // the forces too
      }
    }
  }
  CHECK(pushed > 0);
}

TEST_CASE("the surface hash as a whole is charged as one triangle a task, and runs only when the budget affords it",
          "[cycle][threads]") {
  // Work budgets of several sizes a call, and none: where the HashSurface
  // stage fits in what a call has left, it runs on the pool's threads as a
  // whole; elsewhere one triangle a task. One thread takes the whole stage
  // only without a budget. Every call's stage, work, largest charge and
  // outcome, every stage's work and every contact must be those of the
  // one-triangle path (CycleSchedule::whole_surface_hash off) on one thread,
  // both under the paper's tasks and under fine tasks (whose table builds
  // then run at once).
  constexpr std::uint64_t kNoBudget = std::numeric_limits<std::uint64_t>::max();
  std::int64_t whole[2] = {0, 0}, one_by_one[2] = {0, 0};  // [fine], on 2 threads under work budgets
  for (const auto& [name, scene] : test::collision_scenes())
    for (const bool fine : {false, true})
      for (const std::uint64_t units : {std::uint64_t{30}, std::uint64_t{700}, std::uint64_t{20000}, kNoBudget}) {
        INFO(name << (fine ? " fine" : " paper's tasks") << " work " << units);
        using Trace = std::vector<std::tuple<int, std::uint64_t, std::uint64_t, bool>>;
        Trace reference_trace;
        std::vector<Contact> reference_contacts;
        std::array<std::uint64_t, kCostStages> reference_work{};
        for (const int threads : {0, 1, 2}) {  // 0: the reference, one thread, one triangle a task
          INFO("threads " << threads);
          World w = build_world(scene);
          CollisionSettings settings = test::settings_of(w, scene);
          settings.threads = std::max(threads, 1);
          CycleSchedule schedule;
          if (fine) schedule.granularity = TaskGranularity::fine_tasks();
          schedule.whole_surface_hash = threads > 0;
          CollisionCycle cycle(w, settings, DetectionMode::SpatialHash, schedule);
          cycle.begin(w);
          cycle.start_step_costs();
          Trace trace;
          for (bool done = false; !done;) {
            Budget budget = units == kNoBudget ? Budget::unlimited() : Budget::work_units(units);
            done = cycle.advance(w, budget);
            trace.emplace_back(static_cast<int>(cycle.stage()), budget.spent(), budget.max_task_work(), done);
            REQUIRE(trace.size() < 1000000);
          }
          if (threads == 0) {
            CHECK(cycle.whole_surface_hashes() == 0);
            reference_trace = trace;
            reference_contacts = cycle.contacts();
            reference_work = cycle.step_costs().work;
          } else {
            CHECK(trace == reference_trace);
            CHECK(same_contacts(cycle.contacts(), reference_contacts));
            CHECK(cycle.step_costs().work == reference_work);
            if (units == kNoBudget) {
              CHECK(cycle.whole_surface_hashes() == 1);  // on one thread too
            } else if (threads == 1) {
              CHECK(cycle.whole_surface_hashes() == 0);  // one thread under a work budget: never as a whole
            } else {
              whole[fine] += cycle.whole_surface_hashes();
              one_by_one[fine] += cycle.whole_surface_hashes() == 0 && !reference_contacts.empty();
            }
          }
        }
      }
  for (const int fine : {0, 1}) {
    INFO((fine ? "fine tasks" : "paper's tasks"));
    CHECK(whole[fine] > 0);       // some work budgets afforded the whole stage on the pool
    CHECK(one_by_one[fine] > 0);  // and some did not
  }
}

TEST_CASE("threads change nothing when a cycle spans moving steps and re-detects its points", "[cycle][threads]") {
  // A small work budget a step, and the last body moved a little after
  // every step: cycles span steps, so BorderDepth re-detects points detected
  // in earlier steps (some move out) and must run them serially. Every
  // call's work and stage, and every contact field, must be one thread's.
  // The moved body's velocity changes every step too, and the contacts are
  // damped and have friction, so a force computed at an earlier step's
  // velocities (a batch kept past its step) would differ.
  for (const auto& [name, scene] : test::collision_scenes()) {
    INFO(name);
    using Trace = std::vector<std::tuple<int, std::uint64_t, int>>;  // per call: stage after, work, done
    Trace serial_trace;
    std::vector<Contact> serial_contacts;
    bool redetected = false;
    for (const int threads : {1, 2, 3}) {
      INFO("threads " << threads);
      World w = build_world(scene);
      const CollisionSettings settings = damped_settings(w, scene, threads);
      CollisionCycle cycle(w, settings);
      Trace trace;
      for (int cycles = 0; cycles < 3; ++cycles) {
        cycle.begin(w);
        std::int64_t queried_at = -1;  // the step this cycle's queries ended in
        for (bool done = false; !done;) {
          Budget budget = Budget::work_units(400);
          done = cycle.advance(w, budget);
          trace.emplace_back(static_cast<int>(cycle.stage()), budget.spent(), done);
          if (queried_at < 0 && (done || cycle.stage() > CollisionCycle::Stage::QueryPoints)) queried_at = w.step_index;
          if (done && threads == 1)
            for (const Contact& c : cycle.contacts()) redetected |= c.detected_step > queried_at || c.separated;
          step_last_body(w, Vec3(0.0005, -0.0003, 0.0002), 1.0 + 0.1 * static_cast<double>(trace.size()));
          REQUIRE(trace.size() < 1000000);
        }
      }
      if (threads == 1) {
        serial_trace = trace;
        serial_contacts = cycle.contacts();
      } else {
        CHECK(trace == serial_trace);
        CHECK(same_contacts(cycle.contacts(), serial_contacts));
      }
    }
    CHECK(redetected);  // the serial path after a re-detection really ran
  }
}

TEST_CASE("under a wall budget a force is the penalty force at the step its task ran, on any thread count",
          "[cycle][threads]") {
  // On threads the forces are computed ahead in batches, and a wall budget
  // may stop a batch half taken. The bodies move and change speed between
  // steps, and the contacts are damped and have friction, so a force taken
  // from a batch made in an earlier step would not be this step's penalty
  // force. A clock ticking 1 ms a reading, 5 ms a call, stops cycles inside
  // the Forces stage.
  for (const auto& [name, scene] : test::collision_scenes())
    for (const int threads : {1, 2, 3}) {
      INFO(name << ", threads " << threads);
      World w = build_world(scene);
      const CollisionSettings settings = damped_settings(w, scene, threads);
      double now = 0.0;
      const ClockMs clock = [&now] { return now += 1.0; };
      CollisionCycle cycle(w, settings);
      cycle.set_clock(clock);
      int checked = 0, stopped_in_forces = 0;
      for (int cycles = 0; cycles < 2; ++cycles) {
        cycle.begin(w);
        for (bool done = false; !done;) {
          const std::size_t before = cycle.forces_computed();
          Budget budget = Budget::wall_ms(5.0, clock);
          done = cycle.advance(w, budget);
          const std::vector<Contact>& contacts = cycle.contacts();
          for (std::size_t i = before; i < cycle.forces_computed(); ++i, ++checked) {
            const Contact& c = contacts[i];
            CHECK(c.force_n == penalty_force(w, c, settings.response(c.object, c.other), settings.dt_s));
          }
          stopped_in_forces += !done && cycle.stage() == CollisionCycle::Stage::Forces && cycle.forces_computed() > 0;
          step_last_body(w, Vec3(0.0002, -0.0001, 0.0001), 1.0 + 0.1 * static_cast<double>(w.step_index));
          REQUIRE(w.step_index < 1000000);
        }
      }
      if (!cycle.contacts().empty()) {
        CHECK(checked > 0);
        CHECK(stopped_in_forces > 0);  // a step began with the stage half done
      }
    }
}

TEST_CASE("the cycle counts its memory: every per-tet array, a scratch more a thread, its contacts",
          "[cycle][memory][threads]") {
  const test::TestScene scene = test::collision_scenes()[0].second;
  World w = build_world(scene);
  std::size_t tets = 0;
  for (const Body& b : w.bodies) tets += b.mesh->tet_count();
  CollisionSettings settings = test::settings_of(w, scene);
  CollisionCycle one(w, settings);
  // A box (two Vec3), an owner and a query stamp per tet, and the tet
  // table's two buckets a tet (three 32-bit words each): a floor.
  const std::size_t before = one.memory_bytes();
  CHECK(before >= tets * (2 * sizeof(Vec3) + 4 + 4 + 2 * 12));
  settings.threads = 3;
  CollisionCycle three(w, settings);
  CHECK(three.memory_bytes() >= before + 3 * tets * 4);  // each thread's query stamps
  one.begin(w);
  Budget unlimited = Budget::unlimited();
  REQUIRE(one.advance(w, unlimited));
  REQUIRE(!one.contacts().empty());
  CHECK(one.memory_bytes() >= before + one.contacts().size() * sizeof(Contact));
}

TEST_CASE("under a wall budget a batch is sized to the time left", "[cycle][threads]") {
  CHECK(wall_batch_items(3.0, 0.0, 2, 128) == 8);     // nothing measured: 4 a thread
  CHECK(wall_batch_items(3.0, 0.1, 2, 128) == 30);    // 3 ms at 0.1 ms an item
  CHECK(wall_batch_items(100.0, 0.1, 2, 128) == 128);  // never more than the most
  CHECK(wall_batch_items(0.05, 0.1, 2, 128) == 2);    // never less than one a thread
  CHECK(wall_batch_items(-1.0, 0.1, 3, 192) == 3);    // past the limit already: one a thread
  CHECK(wall_batch_items(1.0, 0.1, 4, 2) == 2);       // the most wins over the threads
}

TEST_CASE("a batch is taken in chunks of a quarter of a thread's share, within bounds", "[cycle][threads]") {
  CHECK(batch_chunk(15460, 2, kQueryChunk) == 128);  // the dog pair's queries: capped
  CHECK(batch_chunk(15460, 2, kDepthChunk) == 16);   // costly items keep small chunks
  CHECK(batch_chunk(128, 2, kQueryChunk) == 16);     // a budget's batch: 4 chunks a thread
  CHECK(batch_chunk(800, 2, kQueryChunk) == 100);    // a quarter of each thread's 400
  CHECK(batch_chunk(800, 4, kQueryChunk) == 50);
  CHECK(batch_chunk(3, 2, kQueryChunk) == 16);       // never below 16 items (one chunk here)
  CHECK(batch_chunk(0, 2, kQueryChunk) == 16);
  CHECK(batch_chunk(800, 0, kQueryChunk) == 128);    // no threads counts as one
  CHECK(batch_chunk(800, 2, 4) == 4);                // the most wins over the 16
  CHECK(batch_chunk(800, 2, 0) == 1);                // and a chunk holds at least one item
}

TEST_CASE("a ticking clock interrupts the tet hashing and resumes it next step", "[cycle][granularity]") {
  const test::TestScene scene = test::collision_scenes()[0].second;
  World world = build_world(scene);
  const CollisionSettings settings = test::settings_of(world, scene);
  CollisionCycle fine(world, settings, DetectionMode::SpatialHash, {.granularity = {4, 8, 4}});
  // The clock advances 1 ms a reading; the budget reads it once when created
  // and once after every task, so a 3 ms budget allows exactly 3 tasks.
  double now = 0.0;
  const ClockMs clock = [&now] { return now += 1.0; };
  fine.begin(world);
  Budget first = Budget::wall_ms(3.0, clock);
  CHECK_FALSE(fine.advance(world, first));
  CHECK(fine.stage() == CollisionCycle::Stage::HashTets);  // 12 tets hashed so far
  CHECK(fine.tasks_done() == 3);
  CHECK(first.max_poll_gap_ms() == 1.0);
  Budget second = Budget::wall_ms(3.0, clock);
  CHECK_FALSE(fine.advance(world, second));
  CHECK(fine.stage() == CollisionCycle::Stage::HashTets);  // resumed where it stopped, not restarted
  CHECK(fine.tasks_done() == 6);
  int steps = 2;
  for (bool done = false; !done; ++steps) {
    Budget b = Budget::wall_ms(3.0, clock);
    done = fine.advance(world, b);
    REQUIRE(steps < 100000);
  }
  CollisionCycle paper(world, settings);
  paper.begin(world);
  Budget unlimited = Budget::unlimited();
  REQUIRE(paper.advance(world, unlimited));
  CHECK(found(fine) == found(paper));
  std::size_t tets = 0;
  for (const Body& b : world.bodies) tets += b.mesh->tet_count();
  CHECK(static_cast<std::size_t>(steps) >= (tets + 3) / 4 / 3);  // 4 tets a hashing task, 3 tasks a step
}

TEST_CASE("predicted stops end the step before a task that would overrun; the paper's poll overruns",
          "[cycle][predict]") {
  // The clock advances 1 ms a reading. Within the hashing stage (fine, 4 tets
  // a task) the budget reads it once a task, so every task measures 1 ms. A
  // budget of 3.5 ms: the paper's poll stops after the task that reached it
  // (4 tasks, 4 ms spent, 0.5 over); the prediction stops after 3 (3 ms),
  // because a fourth would end at 4 > 3.5.
  const test::TestScene scene = test::collision_scenes()[0].second;
  for (const bool predict : {false, true}) {
    INFO((predict ? "predicted" : "the paper's poll"));
    World world = build_world(scene);
    CollisionCycle cycle(world, test::settings_of(world, scene), DetectionMode::SpatialHash,
                         {.granularity = {4, 8, 4}, .predict_tasks = predict});
    double now = 0.0;
    const ClockMs clock = [&now] { return now += 1.0; };
    cycle.begin(world);
    Budget zero = Budget::work_units(0);  // one task, unmeasured: a work budget reads no clock
    REQUIRE_FALSE(cycle.advance(world, zero));
    Budget b = Budget::wall_ms(3.5, clock);
    const std::int64_t before = cycle.tasks_done();
    CHECK_FALSE(cycle.advance(world, b));
    CHECK(cycle.stage() == CollisionCycle::Stage::HashTets);
    CHECK(cycle.tasks_done() - before == (predict ? 3 : 4));
    CHECK(b.elapsed_ms() - 1.0 == (predict ? 3.0 : 4.0));  // elapsed_ms() itself reads the clock once
    // A budget smaller than one task: the step's first task still runs.
    Budget tiny = Budget::wall_ms(0.1, clock);
    const std::int64_t at = cycle.tasks_done();
    CHECK_FALSE(cycle.advance(world, tiny));
    CHECK(cycle.tasks_done() - at == 1);
  }
}

TEST_CASE("a wall budget's reserve lowers its limit; elapsed time is not a poll", "[budget]") {
  double now = 0.0;
  const ClockMs clock = [&now] { return now += 1.0; };
  Budget b = Budget::wall_ms(10.0, clock);  // created at 1
  b.reserve_ms(4.0);
  CHECK(b.limit() == 6.0);
  CHECK(b.elapsed_ms() == 1.0);  // read at 2
  CHECK_FALSE(b.expired());      // 3: 2 ms spent
  now += 3.0;
  CHECK(b.max_poll_gap_ms() == 2.0);  // from creation (1) to the poll (3); the elapsed read did not count
  CHECK(b.expired());                 // read at 7: 6 ms spent, the reserved limit
  CHECK(b.max_poll_gap_ms() == 4.0);
  Budget work = Budget::work_units(100);
  work.reserve_ms(50.0);  // no effect on other kinds
  CHECK(work.limit() == 100.0);
  work.charge(7);
  work.charge(3);
  CHECK(work.max_task_work() == 7);
}

TEST_CASE("widened or rehashed queries find what moved since it was hashed; the paper's query misses some",
          "[cycle][granularity][rehash]") {
  // Hash and build (two tasks of an all-in-one fine cycle), then move box b
  // by `cells` cells as one step of 1 ms would, then query: the hash holds
  // b's tets where they were.
  const test::TestScene scene = test::collision_scenes()[0].second;
  // fine = false: the paper's granularity, whose one hashing task makes a
  // table that later steps' widened queries search (it must stay hashed:
  // TetHashDetector::enable_widening; a dense one would refuse them).
  const auto points_after_move = [&](bool widen, bool rehash, double cells, bool fine = true) {
    World world = build_world(scene);
    CycleSchedule schedule{.widen_stale = widen, .rehash_stale = rehash};
    if (fine) schedule.granularity = {std::size_t{1} << 30, std::size_t{1} << 30, std::size_t{1} << 30};
    CollisionCycle cycle(world, test::settings_of(world, scene), DetectionMode::SpatialHash, schedule);
    cycle.begin(world);
    for (int task = 0; task < 2 && cycle.stage() != CollisionCycle::Stage::QueryPoints; ++task) {
      Budget zero = Budget::work_units(0);
      REQUIRE_FALSE(cycle.advance(world, zero));
    }
    REQUIRE(cycle.stage() == CollisionCycle::Stage::QueryPoints);
    const Vec3 move(cells * cycle.settings().detection.cell_size_m, 0.0, 0.0);
    for (std::size_t v = 0; v < world.bodies[1].x_m.size(); ++v) {
      world.bodies[1].x_m[v] += move;
      world.bodies[1].v_m_per_s[v] = move / scene.world.dt_s;
    }
    ++world.step_index;
    Budget unlimited = Budget::unlimited();
    REQUIRE(cycle.advance(world, unlimited));
    if (widen && !rehash) CHECK(cycle.tet_margin_m() == Approx(move.x()));
    if (widen && rehash) CHECK(cycle.tet_margin_m() == 0.0);  // the refresh took the motion off
    std::set<std::tuple<int, int, int, int>> points;
    for (const Contact& c : cycle.contacts())
      if (!c.separated) points.insert({c.object, c.vertex, c.other, c.tet});
    // The truth at the moved positions.
    std::set<std::tuple<int, int, int, int>> truth;
    const CollisionPairs pairs(world);
    for (std::int32_t b = 0; b < 2; ++b)
      for (std::int32_t v = 0; v < static_cast<std::int32_t>(world.bodies[b].x_m.size()); ++v) {
        std::uint64_t work = 0;
        if (const auto hit = brute_force_query_point(world, pairs, b, v, work))
          truth.insert({hit->object, hit->vertex, hit->other, hit->tet});
      }
    return std::make_pair(points, truth);
  };
  // 0.45 cell: under the margin's cap of half a cell, so widening holds.
  const auto [widened, truth] = points_after_move(true, false, 0.45);
  const auto [paper, same_truth] = points_after_move(false, false, 0.45);
  REQUIRE(!truth.empty());
  CHECK(same_truth == truth);
  CHECK(widened == truth);
  CHECK(points_after_move(true, false, 0.45, false).first == truth);  // widened from the paper's one-task hash
  CHECK(points_after_move(false, true, 0.45).first == truth);
  CHECK(points_after_move(true, true, 0.45).first == truth);
  CHECK(paper.size() < truth.size());  // stale cells and AABBs hide some
  for (const auto& p : paper) CHECK(truth.count(p) == 1);  // but what it finds is true
  // 2.3 cells back towards box a: beyond the cap; the refresh still finds everything.
  const auto [rehashed, far_truth] = points_after_move(false, true, -2.3);
  const auto [far_paper, far_same_truth] = points_after_move(false, false, -2.3);
  REQUIRE(!far_truth.empty());
  CHECK(rehashed == far_truth);
  CHECK(far_paper != far_truth);
}

TEST_CASE("a refresh that spans steps resumes where it stopped, then the queries resume where they stopped",
          "[cycle][rehash]") {
  // One task a call (a work budget of 0), 4 tets a task; the world's step
  // index advances between calls, so every query stage is entered stale.
  const test::TestScene scene = test::collision_scenes()[0].second;
  World world = build_world(scene);
  CollisionCycle cycle(world, test::settings_of(world, scene), DetectionMode::SpatialHash,
                       {.granularity = {4, 8, 4}, .rehash_stale = true});
  cycle.begin(world);
  bool saw_refresh = false, resumed_mid_query = false;
  std::size_t queries_before = 0;
  CollisionCycle::Stage before = cycle.stage();
  for (int call = 0; !cycle.done(); ++call) {
    REQUIRE(call < 1000000);
    if (call % 50 == 0) ++world.step_index;  // a new step now and then: positions unchanged
    Budget zero = Budget::work_units(0);
    cycle.advance(world, zero);
    const CollisionCycle::Stage now = cycle.stage();
    if (now == CollisionCycle::Stage::RefreshTets) {
      saw_refresh = true;
      CHECK(cycle.queries_done() >= queries_before);  // the queries' progress is kept
    }
    if (before == CollisionCycle::Stage::BuildOverflow && now == CollisionCycle::Stage::QueryPoints) {
      CHECK(cycle.queries_done() == queries_before);
      resumed_mid_query |= queries_before > 0;
    }
    if (now == CollisionCycle::Stage::QueryPoints) queries_before = cycle.queries_done();
    before = now;
  }
  CHECK(saw_refresh);
  CHECK(resumed_mid_query);
  CollisionCycle paper(world, test::settings_of(world, scene));
  paper.begin(world);
  Budget unlimited = Budget::unlimited();
  REQUIRE(paper.advance(world, unlimited));
  CHECK(found(cycle) == found(paper));  // positions never changed: the paper's contacts and depths
}

TEST_CASE("a refresh longer than a step cannot stall the cycle: one task a step, a new step every task",
          "[cycle][rehash]") {
  // A work budget of 0 runs one task a step, and every call is a new step, so
  // the table is stale before every query. Each refresh takes many steps;
  // still a task of the interrupted stage runs between two refreshes, and
  // the cycle ends with the paper's contacts (positions never change).
  for (const TaskGranularity granularity : {TaskGranularity{}, TaskGranularity{4, 8, 4}}) {
    INFO("tets a task " << granularity.tets_per_task);
    const test::TestScene scene = test::collision_scenes()[0].second;
    World world = build_world(scene);
    CollisionCycle cycle(world, test::settings_of(world, scene), DetectionMode::SpatialHash,
                         {.granularity = granularity, .rehash_stale = true});
    cycle.begin(world);
    int refreshes = 0;
    CollisionCycle::Stage before = cycle.stage();
    for (int call = 0; !cycle.done(); ++call) {
      REQUIRE(call < 2000000);
      ++world.step_index;
      Budget zero = Budget::work_units(0);
      cycle.advance(world, zero);
      const auto refreshing = [](CollisionCycle::Stage s) {
        return s == CollisionCycle::Stage::RefreshTets || s == CollisionCycle::Stage::BuildOverflow;
      };
      refreshes += refreshing(cycle.stage()) && !refreshing(before);
      before = cycle.stage();
    }
    CHECK(refreshes > 1);
    CollisionCycle paper(world, test::settings_of(world, scene));
    paper.begin(world);
    Budget unlimited = Budget::unlimited();
    REQUIRE(paper.advance(world, unlimited));
    CHECK(found(cycle) == found(paper));
  }
}

TEST_CASE("a kept table finds exactly what a fresh hash finds, cycle after cycle, for less hashing work",
          "[cycle][keep_table][threads]") {
  // One cycle a step, the last body moved between steps: a little (0.02
  // cell, a step's motion; most of its tets stay in their cells), then far (2.3 cells: every
  // one of its tets leaves them). keep_table's contacts must be the paper's
  // in every field, its hash work less once it refreshes, and the cycle
  // after the far move must hash afresh (the overflow holds more than the
  // share) and so be charged exactly the paper's hash work. On 2 threads,
  // every cycle's work must be 1 thread's.
  struct Variant {
    const char* name;
    CycleSchedule paper, kept;
  };
  const std::vector<Variant> variants = {
      {"index order", {}, {.keep_table = true}},
      {"fastest first", {.order = WorkOrder::FastestFirst}, {.order = WorkOrder::FastestFirst, .keep_table = true}},
      {"widen_stale + rehash_stale", {.widen_stale = true, .rehash_stale = true},
       {.widen_stale = true, .rehash_stale = true, .keep_table = true}}};
  for (const Variant& variant : variants)
  for (const auto& [name, scene] : test::collision_scenes()) {
    std::vector<std::uint64_t> one_thread_work;  // the kept cycle's hash work, cycle by cycle
    for (const int threads : {1, 2}) {
      INFO(variant.name << ": " << name << ", threads " << threads);
      World w = build_world(scene);
      CollisionSettings settings = test::settings_of(w, scene);
      settings.threads = threads;
      CollisionCycle paper(w, settings, DetectionMode::SpatialHash, variant.paper);
      CollisionCycle kept(w, settings, DetectionMode::SpatialHash, variant.kept);
      const double cell_m = settings.detection.cell_size_m;
      const std::vector<double> moves = {0.0, 0.02, 0.02, -0.03, 2.3, 0.0, -2.3, 0.02};
      Body& moved = w.bodies.back();
      // Tets a refresh revisits (non-degenerate tets of bodies that can move), and the moved body's.
      const auto live_tets = [](const Body& b) {
        return static_cast<std::uint64_t>(std::count(b.mesh->is_degenerate.begin(), b.mesh->is_degenerate.end(), 0));
      };
      std::uint64_t movable_tets = 0;
      for (const Body& b : w.bodies)
        if (!b.passive) movable_tets += live_tets(b);
      const std::uint64_t moved_tets = live_tets(moved);
      for (std::size_t c = 0; c < moves.size(); ++c) {
        INFO("cycle " << c << ", move " << moves[c] << " cell");
        for (Vec3& x : moved.x_m) x.x() += moves[c] * cell_m;
        ++w.step_index;
        std::uint64_t hash_work[2] = {0, 0};
        int i = 0;
        for (CollisionCycle* cycle : {&paper, &kept}) {
          cycle->start_step_costs();
          cycle->begin(w);
          Budget unlimited = Budget::unlimited();
          REQUIRE(cycle->advance(w, unlimited));
          hash_work[i++] = cycle->step_costs().work_of(CostStage::HashTets);
        }
        REQUIRE(same_contacts(kept.contacts(), paper.contacts()));
        // The refresh on the threads: the same work (its boxes checked in
        // parallel, the overflow filled in id order).
        if (threads == 1) one_thread_work.push_back(hash_work[1]);
        else CHECK(hash_work[1] == one_thread_work.at(c));
        const bool after_far = c > 0 && std::abs(moves[c - 1]) > 1.0;
        if (c == 0 || after_far) {
          CHECK(hash_work[1] == hash_work[0]);  // hashed afresh: the paper's work
        } else {
          CHECK(hash_work[1] < hash_work[0]);  // refreshed
        }
        if (std::abs(moves[c]) > 1.0) {  // every tet of the moved body left its cells: at least a cell each
          CHECK(hash_work[1] >= movable_tets + moved_tets);
        }
      }
      CHECK_FALSE(paper.contacts().empty());
    }
  }
}

TEST_CASE("a kept table's refresh in resumable tasks across steps ends with the paper's contacts",
          "[cycle][keep_table][rehash]") {
  // One task a call (a work budget of 0), a new step every 7 calls; the last
  // body moved between cycles only, so each cycle's positions are fixed and
  // its contacts must equal a fresh paper's cycle's. With rehash_stale too,
  // the refresh that opens a cycle is dated by the step it began in, so a
  // refresh before the first query follows when it spanned steps.
  for (const bool rehash : {false, true}) {
    for (const TaskGranularity granularity : {TaskGranularity{}, TaskGranularity{4, 8, 4}}) {
      INFO("rehash_stale " << rehash << ", tets a task " << granularity.tets_per_task);
      const test::TestScene scene = test::collision_scenes()[0].second;
      World world = build_world(scene);
      CollisionCycle cycle(world, test::settings_of(world, scene), DetectionMode::SpatialHash,
                           {.granularity = granularity, .rehash_stale = rehash, .keep_table = true});
      int opening_refreshes = 0;
      for (int c = 0; c < 4; ++c) {
        for (Vec3& x : world.bodies[1].x_m) x.y() += 0.02 * test::settings_of(world, scene).detection.cell_size_m;
        ++world.step_index;
        cycle.begin(world);
        opening_refreshes += cycle.stage() == CollisionCycle::Stage::RefreshTets;
        for (int call = 0; !cycle.done(); ++call) {
          REQUIRE(call < 1000000);
          if (call % 7 == 6) ++world.step_index;  // positions unchanged within the cycle
          Budget zero = Budget::work_units(0);
          cycle.advance(world, zero);
        }
        CollisionCycle paper(world, test::settings_of(world, scene));
        paper.begin(world);
        Budget unlimited = Budget::unlimited();
        REQUIRE(paper.advance(world, unlimited));
        CHECK(found(cycle) == found(paper));
      }
      CHECK(opening_refreshes == 3);  // every cycle after the first
    }
  }
}
