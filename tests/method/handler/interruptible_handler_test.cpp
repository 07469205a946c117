// The interruptible handler: exact equivalence with full without a budget,
// interruption at exactly the budgeted task on an injected clock, resumption,
// budget 0, and stability at the extremes.
#include "method/handler/interruptible_handler.hpp"

#include <catch2/catch.hpp>
#include <map>
#include <memory>
#include <string>

#include "baselines/registry.hpp"
#include "tests/method/test_worlds.hpp"

using namespace tcb;

namespace {

test::TestScene pressed_blocks() {
  test::TestScene scene = test::scene_of({{"floor", "box:size=1x0.1x1,cells=4x1x4", Vec3::Zero(), true},
                                    {"cube", "box:size=0.2x0.2x0.2,cells=4x4x4", Vec3(0.0, 0.14, 0.0)}});
  scene.collision.response_stiffness_n_per_m = 1000.0;
  return scene;
}

// A clock that advances 1 ms every time it is read: the budget reads it once
// when created and once per interruption point, so a budget of B ms allows
// exactly B tasks per step.
struct TickingClock {
  double now = 0.0;
  ClockMs clock() {
    return [this] { return now += 1.0; };
  }
};

// The tasks of one whole cycle of `scene` (interruptible, the paper's tasks).
std::int64_t whole_cycle_tasks(const test::TestScene& scene) {
  World world = build_world(scene.world);
  InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate);
  handler.init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  REQUIRE(handler.step(world, unlimited).cycle_done);
  return handler.cycle().tasks_done();
}

// The work units of one whole cycle of `scene` (full's).
std::uint64_t whole_cycle_work(const test::TestScene& scene) {
  World world = build_world(scene.world);
  auto full = make_handler("full");
  full->init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  return full->step(world, unlimited).work_units;
}

// What a handler step left on the world: every contact force and link.
void clear_contact_forces(World& world) {
  for (Body& b : world.bodies) std::fill(b.contact_force_n.begin(), b.contact_force_n.end(), Vec3::Zero());
  world.contact_links.clear();
}

// The registry's `name` with apply_first on or off, initialised on `world`.
std::unique_ptr<CollisionHandler> with_apply_first(const char* name, bool apply_first, const World& world,
                                                   const test::TestScene& scene) {
  MethodSettings settings(find_method(name).settings);
  settings.set("apply_first", apply_first);
  auto handler = make_handler(name, &settings);
  handler->init(world, test::settings_of(world, scene));
  return handler;
}

// Every field of two links equal, bit for bit.
bool same_link(const ContactLink& x, const ContactLink& y) {
  return x.point_body == y.point_body && x.vertex == y.vertex && x.tet_body == y.tet_body &&
         x.tet_vertices == y.tet_vertices && x.weights == y.weights && x.normal == y.normal && x.depth_m == y.depth_m &&
         x.stiffness_n_per_m == y.stiffness_n_per_m && x.damping_n_s_per_m == y.damping_n_s_per_m;
}

}  // namespace

TEST_CASE("interruptible: the budget stops after exactly k tasks and resumes at k+1", "[interruptible]") {
  const test::TestScene scene = pressed_blocks();
  const std::int64_t total_tasks = whole_cycle_tasks(scene);
  for (int k : {1, 7, 40}) {
    INFO("k = " << k << " point queries in the first step; " << total_tasks << " tasks per cycle");
    World world = build_world(scene.world);
    InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate);
    handler.init(world, test::settings_of(world, scene));
    TickingClock ticking;
    const int per_step = k + 1;  // the first step's tasks: hashing the tets, then k point queries
    Budget first = Budget::wall_ms(per_step, ticking.clock());
    StepReport r = handler.step(world, first);
    CHECK_FALSE(r.cycle_done);
    CHECK(handler.cycle().queries_done() == static_cast<std::size_t>(k));
    world.step(scene.world.dt_s);
    Budget second = Budget::wall_ms(per_step, ticking.clock());
    r = handler.step(world, second);
    CHECK(handler.cycle().queries_done() == static_cast<std::size_t>(k + per_step));  // resumed at k+1
    world.step(scene.world.dt_s);
    int steps = 2;
    while (!r.cycle_done) {
      Budget b = Budget::wall_ms(per_step, ticking.clock());
      r = handler.step(world, b);
      world.step(scene.world.dt_s);
      ++steps;
      REQUIRE(steps < 100000);
    }
    CHECK(r.cycle == 1);
    CHECK(steps == (total_tasks + per_step - 1) / per_step);
  }
}

TEST_CASE("interruptible: budget 0 hashes the tets, then does one task per step; stays finite", "[interruptible]") {
  const test::TestScene scene = pressed_blocks();
  World world = build_world(scene.world);
  InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate);
  handler.init(world, test::settings_of(world, scene));
  for (int s = 1; s <= 200; ++s) {
    Budget zero = Budget::work_units(0);
    const StepReport r = handler.step(world, zero);
    if (s == 1) CHECK(r.work_units > 0);          // the tet hashing is never interrupted
    CHECK(handler.cycle().tasks_done() == s);     // the budget is polled after every task
    world.step(scene.world.dt_s);
    REQUIRE(std::isfinite(world.max_speed_m_per_s()));
  }
}

TEST_CASE("interruptible: a budget far larger than needed behaves like full", "[interruptible]") {
  const test::TestScene scene = pressed_blocks();
  World world = build_world(scene.world);
  InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate);
  handler.init(world, test::settings_of(world, scene));
  Budget huge = Budget::wall_ms(1e9);
  const StepReport r = handler.step(world, huge);
  CHECK(r.cycle_done);
  CHECK(r.estimated_forces == 0);
  CHECK(r.exact_forces > 0);
}

TEST_CASE("interruptible with no budget gives full's forces bit for bit, in both response modes", "[interruptible]") {
  const auto same_links = [](const World& a, const World& b) {
    if (a.contact_links.size() != b.contact_links.size()) return false;
    for (std::size_t i = 0; i < a.contact_links.size(); ++i)
      if (!same_link(a.contact_links[i], b.contact_links[i])) return false;
    return true;
  };
  for (const ResponseMode mode : {ResponseMode::Explicit, ResponseMode::Implicit})
  for (const char* name :
       {"interruptible", "interruptible_no_extrapolation", "interruptible_tracked", "interruptible_prioritized"})
  for (const bool fine : {false, true}) {  // our settings too: a budget never reached changes nothing
    INFO(name << (mode == ResponseMode::Implicit ? " implicit" : " explicit") << (fine ? " fine" : ""));
    test::TestScene scene = pressed_blocks();
    scene.collision.response_mode = mode;
    scene.collision.damping_n_s_per_m = 2.0;  // a damper acts even at depth 0
    World a = build_world(scene.world), b = build_world(scene.world);
    std::size_t links_seen = 0;
    auto full = make_handler("full");
    MethodSettings settings(find_method(name).settings);
    settings.set("fine_tasks", fine);
    settings.set("reserve_apply", fine);
    settings.set("widen_stale", fine);
    settings.set("rehash_stale", fine);
    settings.set("predict_tasks", fine);
    auto interruptible = make_handler(name, &settings);
    full->init(a, test::settings_of(a, scene));
    interruptible->init(b, test::settings_of(b, scene));
    TickingClock ticking;  // with our settings the interruptible side runs under a wall budget never reached,
                           // so the reserve's clock readings and the margins' bookkeeping really run
    for (int s = 0; s < 300; ++s) {
      Budget ua = Budget::unlimited(), ub = fine ? Budget::wall_ms(1e12, ticking.clock()) : Budget::unlimited();
      const StepReport ra = full->step(a, ua);
      const StepReport rb = interruptible->step(b, ub);
      for (std::size_t i = 0; i < a.bodies.size(); ++i) REQUIRE(a.bodies[i].contact_force_n == b.bodies[i].contact_force_n);
      REQUIRE(same_links(a, b));
      REQUIRE(ra.exact_forces == rb.exact_forces);
      links_seen += a.contact_links.size();
      a.step(scene.world.dt_s);
      b.step(scene.world.dt_s);
    }
    for (std::size_t i = 0; i < a.bodies.size(); ++i) CHECK(a.bodies[i].x_m == b.bodies[i].x_m);
    CHECK((links_seen > 0) == (mode == ResponseMode::Implicit));  // the implicit runs really used links
  }
}

TEST_CASE("interruptible stays finite at the extremes", "[interruptible][extremes]") {
  struct Case {
    const char* name;
    double dt_s, density_ratio;
    std::uint64_t budget;
  };
  for (const Case c : {Case{"dt 1e-5", 1e-5, 1.0, 500}, Case{"dt 1e-2", 1e-2, 1.0, 500},
                       Case{"mass ratio 1000:1", 1e-3, 1000.0, 500}, Case{"budget 1 unit", 1e-3, 1.0, 1}}) {
    INFO(c.name);
    test::TestScene scene = pressed_blocks();
    scene.world.dt_s = c.dt_s;
    scene.world.objects[0].passive = false;  // two dynamic bodies: a heavy cube on a light slab
    scene.world.ground = GroundPlane{-0.05, 0.5};
    scene.world.objects[1].material.density_kg_per_m3 *= c.density_ratio;
    World world = build_world(scene.world);
    auto handler = make_handler("interruptible");
    handler->init(world, test::settings_of(world, scene));
    for (int s = 0; s < 300; ++s) {
      Budget budget = Budget::work_units(c.budget);
      handler->step(world, budget);
      world.step(scene.world.dt_s);
      REQUIRE(std::isfinite(world.max_speed_m_per_s()));
    }
  }
}

TEST_CASE("interruptible_tracked: a known contact's depth follows the current positions between cycles",
          "[interruptible]") {
  const test::TestScene scene = pressed_blocks();
  World world = build_world(scene.world);
  InterruptibleHandler handler(InterruptibleHandler::Stale::Track);
  handler.init(world, test::settings_of(world, scene));
  Budget unlimited = Budget::unlimited();
  REQUIRE(handler.step(world, unlimited).cycle_done);  // cycle 1: depths and forces for the pressed points
  Vec3 exact = Vec3::Zero();
  for (const Vec3& f : world.bodies[1].contact_force_n) exact += f;
  REQUIRE(exact.y() > 0.0);  // the floor pushes the cube up
  std::fill(world.bodies[1].contact_force_n.begin(), world.bodies[1].contact_force_n.end(), Vec3::Zero());
  std::fill(world.bodies[0].contact_force_n.begin(), world.bodies[0].contact_force_n.end(), Vec3::Zero());
  // Learn the contacts at the pressed position, then raise the cube by `up`
  // (negative: press it further) before a step whose cycle has no depths yet.
  const auto stale_step = [&](double up) {
    World moved = build_world(scene.world);
    InterruptibleHandler h(InterruptibleHandler::Stale::Track);
    h.init(moved, test::settings_of(moved, scene));
    Budget u = Budget::unlimited();
    h.step(moved, u);
    for (auto& b : moved.bodies) std::fill(b.contact_force_n.begin(), b.contact_force_n.end(), Vec3::Zero());
    for (Vec3& x : moved.bodies[1].x_m) x.y() += up;
    Budget zero = Budget::work_units(0);  // only the tet hashing: no point has a depth in this cycle yet
    const StepReport r = h.step(moved, zero);
    CHECK_FALSE(r.cycle_done);
    Vec3 f = Vec3::Zero();
    for (const Vec3& g : moved.bodies[1].contact_force_n) f += g;
    return std::make_pair(f, r.estimated_forces);
  };
  const auto [deeper, n_deeper] = stale_step(-0.002);   // 2 mm further in
  const auto [shallower, n_out] = stale_step(0.02);     // 2 cm up: out of contact
  const auto [same, n_same] = stale_step(0.0);
  CHECK(n_deeper > 0);
  CHECK(deeper.y() > same.y());                 // pushed in further: a larger force at once
  CHECK(same.y() == Approx(exact.y()).epsilon(1e-9));  // not moved: the exact force again
  CHECK(shallower.y() == 0.0);                  // tracked out of contact: no force
  CHECK(n_out == 0);
}

TEST_CASE("interruptible_tracked keeps a contact its cycles lost for keep_lost_cycles cycles, inert while out",
          "[interruptible]") {
  const test::TestScene scene = pressed_blocks();
  const auto clear = [](World& w) {
    for (auto& b : w.bodies) std::fill(b.contact_force_n.begin(), b.contact_force_n.end(), Vec3::Zero());
  };
  const auto force_on_cube = [](const World& w) {
    Vec3 f = Vec3::Zero();
    for (const Vec3& g : w.bodies[1].contact_force_n) f += g;
    return f;
  };
  const auto lift = [](World& w, double up) {
    for (Vec3& x : w.bodies[1].x_m) x.y() += up;
  };
  // Cycle 1 finds the pressed contacts; then `lost` completed cycles run with
  // the cube lifted 2 cm (out of contact, so they find nothing); then the cube
  // is put back and a step runs whose cycle has no depth yet (budget 0).
  const auto back_after = [&](std::int64_t keep, int lost) {
    World w = build_world(scene.world);
    InterruptibleHandler h(InterruptibleHandler::Stale::Track, {.keep_lost_cycles = keep});
    h.init(w, test::settings_of(w, scene));
    Budget u = Budget::unlimited();
    REQUIRE(h.step(w, u).cycle_done);
    const Vec3 exact = force_on_cube(w);
    for (int c = 0; c < lost; ++c) {
      clear(w);
      lift(w, 0.02);
      Budget all = Budget::unlimited();
      REQUIRE(h.step(w, all).cycle_done);
      CHECK(force_on_cube(w) == Vec3::Zero());  // lifted: the completed cycle's answer, nothing
      lift(w, -0.02);
    }
    clear(w);
    Budget zero = Budget::work_units(0);
    const StepReport r = h.step(w, zero);
    CHECK_FALSE(r.cycle_done);
    return std::make_tuple(force_on_cube(w), exact, r.estimated_forces);
  };
  {
    const auto [f, exact, n] = back_after(1, 1);  // lost by one cycle, kept for one: tracked again at once
    REQUIRE(exact.y() > 0.0);
    CHECK(n > 0);
    CHECK(f.y() == Approx(exact.y()).epsilon(1e-9));
  }
  {
    const auto [f, exact, n] = back_after(0, 1);  // the paper's rule: forgotten when a cycle misses it
    CHECK(n == 0);
    CHECK(f == Vec3::Zero());
  }
  {
    const auto [f, exact, n] = back_after(1, 2);  // lost by two cycles, kept for one: forgotten
    CHECK(n == 0);
    CHECK(f == Vec3::Zero());
  }
  {
    const auto [f, exact, n] = back_after(2, 2);
    CHECK(n > 0);
    CHECK(f.y() == Approx(exact.y()).epsilon(1e-9));
  }
}

TEST_CASE("reserve_apply stops the cycle early by the time applying took in the step before", "[interruptible]") {
  // On a clock that advances 1 ms a reading, applying the forces is measured
  // between two readings: 1 ms. A 6 ms budget allows 6 tasks; with the
  // reserve, the step after gets 6 - 1 = 5 tasks (without it, 6 again).
  const test::TestScene scene = pressed_blocks();
  const auto tasks_in_two_steps = [&](bool reserve) {
    World world = build_world(scene.world);
    InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate, {.reserve_apply = reserve});
    handler.init(world, test::settings_of(world, scene));
    TickingClock ticking;
    std::vector<std::int64_t> tasks;
    for (int s = 0; s < 2; ++s) {
      Budget b = Budget::wall_ms(6.0, ticking.clock());
      REQUIRE_FALSE(handler.step(world, b).cycle_done);
      tasks.push_back(handler.cycle().tasks_done());
    }
    return tasks;
  };
  CHECK(tasks_in_two_steps(false) == std::vector<std::int64_t>{6, 12});
  CHECK(tasks_in_two_steps(true) == std::vector<std::int64_t>{6, 11});
  // Under a work budget the reserve does nothing (no clock to measure with):
  // the same tasks a step with and without it.
  const auto tasks_under_work = [&](bool reserve) {
    World world = build_world(scene.world);
    InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate, {.reserve_apply = reserve});
    handler.init(world, test::settings_of(world, scene));
    std::vector<std::int64_t> tasks;
    for (int s = 0; s < 3; ++s) {
      Budget b = Budget::work_units(40);
      handler.step(world, b);
      tasks.push_back(handler.cycle().tasks_done());
    }
    return tasks;
  };
  const auto without = tasks_under_work(false);
  CHECK(without[1] > without[0]);  // the cycle spans the steps
  CHECK(tasks_under_work(true) == without);
}

namespace {

// The forces one handler step leaves on a world: every body's contact forces
// and the links, as plain numbers.
struct AppliedForces {
  std::vector<std::vector<Vec3>> contact_force_n;
  std::vector<ContactLink> links;
  std::int64_t exact = 0, estimated = 0;
};

AppliedForces take_forces(World& world, const StepReport& r) {
  AppliedForces f;
  for (const Body& b : world.bodies) f.contact_force_n.push_back(b.contact_force_n);
  f.links.swap(world.contact_links);
  clear_contact_forces(world);
  f.exact = r.exact_forces;
  f.estimated = r.estimated_forces;
  return f;
}

bool same_forces(const AppliedForces& a, const AppliedForces& b) {
  if (a.contact_force_n != b.contact_force_n || a.links.size() != b.links.size() || a.exact != b.exact ||
      a.estimated != b.estimated)
    return false;
  for (std::size_t i = 0; i < a.links.size(); ++i)
    if (!same_link(a.links[i], b.links[i])) return false;
  return true;
}

}  // namespace

TEST_CASE("apply_first applies in step k+1 what the paper's order applies in step k, on a world at rest",
          "[interruptible][apply_first]") {
  // The world is not stepped, so positions and velocities are the same in
  // every step and only the order differs: apply_first applies the cycle as
  // the last step left it, the paper's order as this step leaves it. Without
  // extrapolation (which extrapolates to the step the force acts in) the
  // forces must then be the same, one step apart, bit for bit; across several
  // cycles, with steps that complete one.
  for (const ResponseMode mode : {ResponseMode::Explicit, ResponseMode::Implicit})
  for (const char* name : {"interruptible_no_extrapolation", "interruptible_tracked"}) {
    INFO(name << (mode == ResponseMode::Implicit ? " implicit" : " explicit"));
    test::TestScene scene = pressed_blocks();
    scene.collision.response_mode = mode;
    scene.collision.damping_n_s_per_m = 2.0;
    // A quarter of a whole cycle's work a step: a cycle spans about 4 steps.
    const std::uint64_t cycle_work = whole_cycle_work(scene);
    const auto run = [&](bool apply_first) {
      World world = build_world(scene.world);
      auto handler = with_apply_first(name, apply_first, world, scene);
      std::vector<AppliedForces> steps;
      std::int64_t cycles_done = 0;
      for (int s = 0; s < 60; ++s) {
        Budget b = Budget::work_units(cycle_work / 4);
        const StepReport r = handler->step(world, b);
        cycles_done += r.cycle_done;
        steps.push_back(take_forces(world, r));
      }
      return std::pair{steps, cycles_done};
    };
    const auto [paper, paper_cycles] = run(false);
    const auto [first, first_cycles] = run(true);
    CHECK(paper_cycles >= 8);  // several cycles, each over several steps
    CHECK(first_cycles == paper_cycles);
    CHECK(first[0].exact + first[0].estimated == 0);  // nothing known before the first cycle
    std::int64_t forces = 0;
    for (std::size_t k = 0; k + 1 < paper.size(); ++k) {
      INFO("step " << k);
      REQUIRE(same_forces(first[k + 1], paper[k]));
      forces += paper[k].exact;
    }
    CHECK(forces > 0);
  }
  // With extrapolation the stale forces differ (each is extrapolated to the
  // step it acts in), but which points get which kind of force does not.
  const test::TestScene scene = pressed_blocks();
  const std::uint64_t cycle_work = whole_cycle_work(scene);
  const auto counts = [&](bool apply_first) {
    World world = build_world(scene.world);
    auto handler = with_apply_first("interruptible", apply_first, world, scene);
    std::vector<std::pair<std::int64_t, std::int64_t>> c;
    for (int s = 0; s < 60; ++s) {
      Budget b = Budget::work_units(cycle_work / 4);
      const StepReport r = handler->step(world, b);
      c.emplace_back(r.exact_forces, r.estimated_forces);
      clear_contact_forces(world);
    }
    return c;
  };
  const auto paper = counts(false), first = counts(true);
  std::int64_t estimated = 0;
  for (std::size_t k = 0; k + 1 < paper.size(); ++k) {
    CHECK(first[k + 1] == paper[k]);
    estimated += paper[k].second;
  }
  CHECK(estimated > 0);
}

TEST_CASE("apply_first: after a cycle completes, its contacts alone act, not the older history", "[interruptible][apply_first]") {
  // Cycle 1 finds the pressed cube; cycle 2, with the cube lifted 2 cm,
  // finds nothing. The step after cycle 2 applies cycle 2's answer (nothing),
  // though cycle 1's points still have their history at that moment; with
  // the budget 0, the next cycle has no depth to add.
  const test::TestScene scene = pressed_blocks();
  for (const char* name : {"interruptible", "interruptible_tracked"}) {
    INFO(name);
    World world = build_world(scene.world);
    auto handler = with_apply_first(name, true, world, scene);
    Budget all = Budget::unlimited();
    REQUIRE(handler->step(world, all).cycle_done);
    const auto lift = [&](double up) {
      for (Vec3& x : world.bodies[1].x_m) x.y() += up;
    };
    lift(0.02);
    Budget all_again = Budget::unlimited();
    const StepReport second = handler->step(world, all_again);
    REQUIRE(second.cycle_done);
    // Cycle 1's contacts, applied a step late (tracked: their depths carried
    // to the lifted cube are <= 0, so none acts).
    CHECK((second.exact_forces > 0) == (std::string(name) == "interruptible"));
    CHECK(handler->contacts().empty());
    lift(-0.02);  // back in contact: a stale force would now push
    clear_contact_forces(world);
    Budget zero = Budget::work_units(0);
    const StepReport third = handler->step(world, zero);
    CHECK_FALSE(third.cycle_done);
    CHECK(third.exact_forces + third.estimated_forces == 0);
    CHECK(world.contact_links.empty());
  }
}

TEST_CASE("apply_first applies before the step's first poll; the paper's order after its last",
          "[interruptible][apply_first]") {
  // The clock notes how many points had a contact force when it was read: the
  // budget reads it at creation and at every poll.
  const test::TestScene scene = pressed_blocks();
  // A budget of a quarter of a whole cycle's tasks (the clock ticks 1 ms a
  // reading, a reading a task): a cycle spans about 4 steps.
  const std::int64_t cycle_tasks = whole_cycle_tasks(scene);
  for (const bool apply_first : {false, true}) {
    INFO((apply_first ? "apply_first" : "the paper's order"));
    World world = build_world(scene.world);
    auto handler = with_apply_first("interruptible", apply_first, world, scene);
    double now = 0.0;
    std::vector<std::size_t> pushed_at_reads;
    const ClockMs clock = [&] {
      std::size_t pushed = world.contact_links.size();
      for (const Body& b : world.bodies)
        for (const Vec3& f : b.contact_force_n) pushed += f != Vec3::Zero();
      pushed_at_reads.push_back(pushed);
      return now += 1.0;
    };
    std::int64_t steps_with_forces = 0, polls_after_forces = 0;
    for (int s = 0; s < 40; ++s) {
      pushed_at_reads.clear();
      Budget b = Budget::wall_ms(static_cast<double>(cycle_tasks / 4), clock);
      const StepReport r = handler->step(world, b);
      // The creation, then a poll after every task but one that completes
      // the cycle.
      REQUIRE_FALSE(pushed_at_reads.empty());
      CHECK(pushed_at_reads.front() == 0);
      const bool applied = r.exact_forces + r.estimated_forces > 0;
      steps_with_forces += applied;
      // Every poll of the step saw the step's forces already applied, or none.
      for (std::size_t i = 1; i < pushed_at_reads.size(); ++i) {
        CHECK((pushed_at_reads[i] > 0) == (apply_first && applied));
        polls_after_forces += pushed_at_reads[i] > 0;
      }
      world.step(scene.world.dt_s);
    }
    CHECK(steps_with_forces > 10);
    CHECK((polls_after_forces > 10) == apply_first);
  }
}

TEST_CASE("extrapolation continues from the step a cycle completed in, though its history is recorded a step later",
          "[interruptible]") {
  // Cycles complete in steps 1 and 2 (the cube pressed 1 mm deeper for the
  // second), so a point in both has f1 = B (step 2), f2 = A, n = 1; step 3
  // runs no depth (budget 0) and extrapolates B + (3 - 2) (B - A). Under
  // implicit response that force is a link whose depth is its normal part
  // over the stiffness.
  test::TestScene scene = pressed_blocks();
  scene.collision.response_mode = ResponseMode::Implicit;
  World world = build_world(scene.world);
  InterruptibleHandler handler(InterruptibleHandler::Stale::Extrapolate);
  handler.init(world, test::settings_of(world, scene));
  const auto forces_of_cycle = [&] {
    std::map<std::pair<std::int32_t, std::int32_t>, Vec3> f;
    for (const Contact& c : handler.contacts())
      if (c.depth_source != DepthSource::None) f[{c.object, c.vertex}] = c.force_n;
    return f;
  };
  Budget all = Budget::unlimited();
  REQUIRE(handler.step(world, all).cycle_done);
  const auto a = forces_of_cycle();
  clear_contact_forces(world);
  for (Vec3& x : world.bodies[1].x_m) x.y() -= 0.001;
  Budget all_again = Budget::unlimited();
  REQUIRE(handler.step(world, all_again).cycle_done);
  const auto b = forces_of_cycle();
  clear_contact_forces(world);
  Budget zero = Budget::work_units(0);
  const StepReport r = handler.step(world, zero);
  REQUIRE_FALSE(r.cycle_done);
  REQUIRE(r.estimated_forces > 0);
  const double k = scene.collision.response_stiffness_n_per_m;
  std::size_t checked = 0, moved = 0;
  for (const ContactLink& link : world.contact_links) {
    const auto in_a = a.find({link.point_body, link.vertex}), in_b = b.find({link.point_body, link.vertex});
    if (in_a == a.end() || in_b == b.end()) continue;
    const Vec3 f = 2.0 * in_b->second - in_a->second;
    CHECK(link.depth_m * k == Approx(f.dot(link.normal)).epsilon(1e-12));
    moved += (in_b->second - in_a->second).norm() > 1e-3 * in_b->second.norm();
    ++checked;
  }
  CHECK(checked > 0);
  CHECK(moved > 0);  // A and B differ: the check tells the step apart
}

TEST_CASE("interruptible counts its force histories in its memory, beside the cycle's", "[interruptible][memory]") {
  const test::TestScene scene = test::collision_scenes()[0].second;
  World world = build_world(scene);
  std::size_t vertices = 0;
  for (const Body& b : world.bodies) vertices += b.x_m.size();
  for (const auto stale : {InterruptibleHandler::Stale::Extrapolate, InterruptibleHandler::Stale::Track}) {
    InterruptibleHandler handler(stale);
    handler.init(world, test::settings_of(world, scene));
    // An index into the dense histories and a "last applied" step per vertex
    // (the histories themselves are empty before a cycle completes); Track
    // keeps a contact per vertex as well.
    const std::size_t own = vertices * (sizeof(std::int32_t) + sizeof(std::int64_t)) +
                            (stale == InterruptibleHandler::Stale::Track ? vertices * sizeof(Contact) : 0);
    CHECK(*handler.memory_bytes() >= handler.cycle().memory_bytes() + own);
  }
}
