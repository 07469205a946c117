#pragma once
/// One collision cycle (detection, penetration depth, response: the paper,
/// fig. 2) written once as a sequence of small resumable tasks, so every
/// handler runs the same algorithm and only the schedule differs.
///
/// Stages and their tasks; the budget is polled after every task (the
/// interruption points of the paper):
///   Prioritize   (WorkOrder::FastestFirst only) the points to query ordered
///                by speed, fastest first: ONE task, charged a unit a point
///   HashTets     all tets into the spatial hash, and the table built: ONE
///                task, not interruptible, done once per cycle and not
///                repeated when resuming (the paper's granularity). With
///                TaskGranularity::fine() (our setting, not the paper's):
///                tets_per_task tets a task, then BuildTetHash
///   BuildTetHash the tet table built, build_visits_per_task entries a task (fine only)
///   QueryPoints  one point query per task
///   HashSurface  one surface triangle per task (bodies some point is inside);
///                the last one builds the table (the paper's granularity), or
///                BuildSurfaceHash follows (fine)
///   BuildSurfaceHash  as BuildTetHash, for the surface table (fine only)
///   BorderDepth  one colliding point's border-edge work per task (the
///                paper's granularity), or one border edge per task (fine:
///                a point's edges may then span steps, each read at the
///                positions of its step, as the tets of a fine hash are)
///   Propagate    one propagated point per task, layer by layer; each layer's
///                points are found in the task that ends the layer before
///                (the paper's granularity: layer 1 from every contact, a
///                later one from the layer before's points) or by BuildLayer
///                tasks over every contact (fine)
///   BuildLayer   the next layer's points, layer_scan_per_task contacts a task
///                (fine only; a layer's points then come in the order found,
///                which gives the same depths: no point of a layer reads another)
///   Forces       one penalty force per task
///   RefreshTets  (setting rehash_stale, ours) entered before a task that
///                queries the tet table (a point query, or the re-detection
///                that opens a contact's border work) in a step later than
///                the table's positions, at most once a step and never twice
///                without a task of the interrupted stage in between (so a
///                refresh longer than a step cannot stall the cycle): every movable tet's box
///                refreshed and the ones that left their cells entered into
///                the overflow table (tet_hash_detection.hpp), tets_per_task
///                tets a task (all in one task at the paper's granularity);
///                then BuildOverflow, and the interrupted stage resumes where
///                it stopped. Reported under hash_tets.
///   BuildOverflow the overflow table built, as BuildTetHash
///   (setting keep_table, ours) a cycle whose last table is kept opens with
///                RefreshTets in place of HashTets: at the paper's granularity
///                one task with the overflow's build, as HashTets; with fine
///                tasks RefreshTets and BuildOverflow pieces, in place of
///                HashTets and BuildTetHash. Then QueryPoints from its first
///                point. This refresh may be followed at once by a
///                rehash_stale refresh (without a query task between) when it
///                spanned steps, as a fine hash may
/// A task always reads the world's current positions: work resumed in a later
/// step uses the positions of that step. In particular a point detected in an
/// earlier step is re-detected (one point query) before its border-edge work:
/// it may have moved to another tet, or out of the object, since; then it is
/// marked separated and is inert (no depth, no force, not a colliding
/// neighbour). Without this, a point that drifted just outside a face while the
/// cycle was interrupted kept only a grazing border edge through a side face
/// and got a depth of a whole edge length. A cycle that completes within one
/// step never re-detects. Nothing is applied to the world here: handlers
/// decide which forces to apply.
///
/// Under fine granularity a cycle may hash its tets over several steps, each
/// tet with the positions of the step that hashed it; queries start once the
/// whole table is built. With unchanged positions the contacts are exactly
/// the paper's granularity's (and with an unlimited budget, where a cycle
/// runs within one step, the two are bit for bit the same run). Work units
/// are the same under both: building a table is not charged (its cost
/// follows the inserts already charged).
///
/// With settings.threads > 1 (spatial hash only) the QueryPoints stage answers
/// a batch of queries ahead on a WorkerPool (all remaining points without a
/// budget; under a work budget 64 a thread, at most the units left), then takes the answers one a task in the
/// serial order with each query's own work: contacts, work units and where a
/// budget stops are those of one thread. A batch holds for its step only and
/// is dropped by begin() and by a refresh; the batch's time falls in the task
/// that starts it, so under wall budgets a task is a batch long, and a batch
/// is sized to the time left at the recent time per item (at least one item
/// a thread, at most 64 a thread). The paper's
/// HashTets task (not fine tasks, whose pieces stay serial) also runs on the
/// pool (TetHashDetector::hash_tets with a pool): the same table, boxes and
/// work units on any thread count (without a budget and unwidened, a table
/// without the tets, or cells of tets, no query point reaches: the same
/// answers and work); so does a RefreshTets task at that granularity
/// (TetHashDetector::refresh_tets: the boxes checked on the pool, the
/// overflow filled in slot order: the same overflow and work units). The paper's BorderDepth tasks (not fine tasks) are batched the
/// same way when every contact from the cursor on was detected at the
/// current step's positions, so that no task ahead re-detects a point (a
/// re-detection changes what later depths read): each depth is computed on a
/// copy of its contact and taken in order, one a task, with its own work.
/// A cycle resumed in a later step re-detects its points, and its depths run
/// serially. The HashSurface stage runs on the pool as a whole
/// (SurfaceHash::hash_all: the same table) when the step's budget affords it:
/// without a budget, or under a work budget whose units left exceed the
/// stage's work (summed on the pool first), so no poll among its tasks would
/// stop it; each triangle's work is charged as its own task would be, and
/// the table is built at once (under fine tasks no BuildSurfaceHash tasks
/// follow: they charge nothing). Under a wall budget it stays one triangle a
/// task. The Forces stage's penalty forces are computed ahead in batches
/// as the point queries are, in every step a cycle runs them (a force reads
/// its own contact and the world only; the stage's 2-thread speed-up went
/// from 0.96-1.09 to 1.48-1.79 in most rounds). Propagation stays on one
/// thread: batched, its stage gained nothing measurable
/// (docs/performance.md, "Tried and not kept").
///
/// On one thread (no pool) the HashSurface stage runs as a whole too, but
/// only without a budget (on a pool of the calling thread, whose owners'
/// build keeps its accesses in a core's cache): the same table, work and
/// contacts. Under a work budget the pass that would sum the stage's work
/// first would be paid on one thread every cycle, with no gain measured, so
/// there it stays one triangle a task, as under a wall budget.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "method/depth/penetration_depth.hpp"
#include "method/handler/budget.hpp"
#include "method/handler/collision_settings.hpp"
#include "method/handler/stage_costs.hpp"
#include "sim/parallel/worker_pool.hpp"

namespace tcb {

enum class DetectionMode { SpatialHash, BruteForce };

/// In which order a cycle queries its points (and so finds, measures and
/// responds to them): by (body, vertex) index, the paper's; or fastest first
/// (ours, the variant interruptible_prioritized; the paper's future work:
/// "prioritizing objects with high velocities"). Speed is the vertex's speed
/// in the world frame: right when the partners are slow or at rest (the
/// fast sphere and its passive torus); two bodies moving fast together would
/// be ordered by their common speed. Ties keep index order. When the cycle
/// completes, its contacts are put back in (body, vertex) order, so with an
/// unlimited budget the forces are bit for bit the paper's order's.
enum class WorkOrder { Index, FastestFirst };

/// How small the cycle's tasks are (see above). Default: the paper's.
struct TaskGranularity {
  std::size_t tets_per_task = 0;          ///< 0: all tets and the build in one task
  std::size_t build_visits_per_task = 0;  ///< entries a build task visits (fine only)
  std::size_t layer_scan_per_task = 0;    ///< contacts a BuildLayer task scans (fine only)
  bool fine() const { return tets_per_task > 0; }
  /// Ours. Measured (summary max_task_work): the largest task of plates20 and
  /// sneaker_grass falls from 63,000-90,000 work units (the one hashing task)
  /// to 80-200 (one border edge). Building a table charges no work,
  /// so its tasks' size shows only in time.
  /// The sizes: a build task visits its entries in random bucket order,
  /// about three cache misses a visit, and tasks of 2048 visits took up to
  /// 370 us on sneaker_grass (steps.csv's hash_tets time in steps that did
  /// nothing else); hence 128. The tet tasks went from 16 tets to 4 with
  /// them, a judgement: issue 12's note measured the two changes together.
  static TaskGranularity fine_tasks() { return {4, 128, 32}; }
};

/// keep_table: the share of all tets in the last refresh's overflow above
/// which the next cycle hashes afresh. A judgement, see CycleSchedule.
inline constexpr double kKeepTableRehashShare = 0.125;

/// How a cycle schedules its work: the paper's by default. Every field is a
/// setting of ours (method/handler/interruptible_handler.hpp).
struct CycleSchedule {
  TaskGranularity granularity{};
  WorkOrder order = WorkOrder::Index;
  /// Widened queries (setting widen_stale): once a cycle spans steps, the
  /// tets and surface triangles it hashed earlier have moved. The cycle keeps
  /// a bound on how far, the sum over the steps since each hash began of
  /// dt x the fastest vertex's speed (exact for the integrators here, where
  /// x+ = x + dt v+), and grows every later point query and border-edge
  /// search by it, so nothing that now collides is missed for being hashed
  /// where it was. The bound is capped at half a cell (beyond it, it no
  /// longer holds): uncapped, slow wide queries lengthen the cycle, which
  /// widens them further. The paper queries the point's own cell (margin 0).
  bool widen_stale = false;
  /// Rehashed tets (setting rehash_stale), the alternative to widening for
  /// the tet table: before the cycle queries in a step later than the one
  /// its tet table (or last refresh) holds the positions of, it refreshes
  /// the table (stage RefreshTets above), so queries find exactly brute
  /// force's tets at the positions of the refresh, however far anything
  /// moved. A refresh that spans steps holds each tet at the positions of
  /// the step that revisited it, and nothing covers the motion since unless
  /// widen_stale is set too: then the tet margin after a refresh is the
  /// motion since the refresh began. The surface table is not refreshed
  /// (widen_stale covers it).
  bool rehash_stale = false;
  /// Kept tet table (setting keep_table, ours; not the paper's schedule,
  /// which hashes every tet afresh in every cycle): a cycle after the first
  /// opens with a refresh of the table the last one built (stage RefreshTets:
  /// every movable tet's current box, the tets that left the cells they were
  /// hashed in entered into the overflow table), as a tree library refits
  /// its tree instead of rebuilding it. Queries then find exactly what a
  /// fresh hash finds (tet_hash_detection.hpp, 1b), so a cycle that runs
  /// within one step has the paper's contacts, depths and forces. Its work
  /// and time differ: hash_tets charges a unit a movable tet and one an
  /// overflow cell, against one a cell of every tet; while the overflow
  /// holds tets, every query charges a unit more for its cell there, and
  /// candidates met in a different order can change what the early stop
  /// saves. So under a budget the cycle stops elsewhere than the paper's. The
  /// table is hashed afresh in the first cycle, after a hash that did not
  /// complete, and whenever the last refresh put more than
  /// keep_table_rehash_share of all tets into the overflow (each of its tets
  /// is inserted again every cycle, and queries search two tables). The
  /// default 1/8 is a judgement: on the moving dog pair
  /// (micro_collision_cycle BM_DogPairMoving) shares from 1/32 to 1/4 gave
  /// cycles within the machine's noise of each other, 1/2 a slower one.
  bool keep_table = false;
  /// keep_table's share (see above); a field so that benchmarks can weigh
  /// other values (micro_collision_cycle's BM_DogPairMoving), not a setting.
  double keep_table_rehash_share = kKeepTableRehashShare;
  /// Predicted stops (setting predict_tasks, ours): under a wall budget the
  /// paper polls after a task and so overruns by the part of the last task
  /// past the limit. With this set, after every task the cycle also stops
  /// when the next task, predicted to take as long as the recent tasks of
  /// its stage (per stage, an average of the measured times that forgets:
  /// 0.8 old + 0.2 new), would end past the limit. Never before the step's
  /// first task, so every step advances. Reads no extra clock (task times
  /// are the gaps between the budget's polls; the step's first gap, which
  /// also holds the handler's work before the cycle, is not counted).
  bool predict_tasks = false;
  /// The HashSurface stage at once when the budget affords it (see above):
  /// the same table, work and stops as one triangle a task, sooner. A field
  /// so that tests and benchmarks can run the one-triangle path beside it
  /// (false), not a setting.
  bool whole_surface_hash = true;
};

class CollisionCycle {
 public:
  enum class Stage {
    Idle,
    Prioritize,
    HashTets,
    BuildTetHash,
    QueryPoints,
    HashSurface,
    BuildSurfaceHash,
    BorderDepth,
    Propagate,
    BuildLayer,
    Forces,
    RefreshTets,
    BuildOverflow,
    Done
  };

  CollisionCycle(const World& world, CollisionSettings settings, DetectionMode mode = DetectionMode::SpatialHash,
                 CycleSchedule schedule = {});
  /// The motion bound of widen_stale (m) since the tet hash began.
  double tet_margin_m() const { return m_tet_margin_m; }

  /// Starts a new cycle (the previous one's results are dropped).
  void begin(const World& world);
  /// Runs tasks until the cycle is done (true) or the budget has expired after
  /// a task (false). Charges every task's work to the budget.
  bool advance(World& world, Budget& budget);

  /// This step's stage costs (stage_costs.hpp), accumulated by advance() on
  /// `clock` since the last start_step_costs(). The handler adds `apply`.
  void start_step_costs() { m_step_costs = StageCosts{}; }
  const StageCosts& step_costs() const { return m_step_costs; }
  void set_clock(ClockMs clock) { m_clock = std::move(clock); }
  const ClockMs& clock() const { return m_clock; }

  Stage stage() const { return m_stage; }
  bool done() const { return m_stage == Stage::Done; }
  std::int64_t number() const { return m_number; }  ///< 1 for the first cycle
  const std::vector<Contact>& contacts() const { return m_contacts; }
  /// Contacts that ended the cycle without a depth (no border path).
  std::int64_t depth_fallback() const;
  const CollisionSettings& settings() const { return m_settings; }
  /// Progress, for schedules and tests: tasks run in this cycle, points
  /// queried, and how many contacts (a prefix of contacts()) have their force.
  /// Tasks run since begin(). Under fine tasks, a surface hash run as a
  /// whole skips the uncharged BuildSurfaceHash tasks, so the count (not the
  /// work, nor where budgets stop) depends on whether the stage ran as a
  /// whole (above: the thread count and the budget decide).
  std::int64_t tasks_done() const { return m_tasks; }
  /// How many tet hashes completed afresh (HashTets, or BuildTetHash's end)
  /// since construction; with keep_table, the other cycles refreshed.
  std::int64_t fresh_tet_hashes() const { return m_fresh_tet_hashes; }
  /// How many surface hashes ran as a whole, on any thread count (see above).
  std::int64_t whole_surface_hashes() const { return m_whole_surface_hashes; }
  /// Heap bytes of everything the cycle holds: both hashes, boxes, queries,
  /// contacts and their lookup, batches and every thread's scratch (the
  /// world's meshes and positions are not the cycle's).
  std::size_t memory_bytes() const;
  std::size_t queries_done() const;
  std::size_t forces_computed() const;

 private:
  void enter(Stage stage, const World& world);
  /// What every task leaves behind, whichever loop ran it: its work charged
  /// to the budget and to its stage, and one more task counted.
  void count_task(Budget& budget, CostStage stage, std::uint64_t work) {
    budget.charge(work);
    m_step_costs.work_of(stage) += work;
    ++m_tasks;
  }
  void add_contact(const Contact& c);
  std::optional<Contact> detect(const World& world, std::int32_t body, std::int32_t vertex, std::uint64_t& work);
  void build_next_layer(const World& world);
  void prioritize(const World& world);
  void enter_detection(const World& world);
  void grow_margins(const World& world);
  void warm_up(const World& world);
  bool needs_refresh(const World& world) const;
  /// A refresh's overflow is built: the table counts as fresh (see RefreshTets).
  void end_refresh(const World& world);
  void restore_index_order();
  void start_layer_scan();
  bool scan_layer_some(const World& world, std::size_t max_contacts);
  /// Queues each neighbour of c that the next layer takes (c of the layer
  /// just finished, with a depth; each neighbour once a scan).
  void queue_neighbours(const World& world, const Contact& c);
  bool batch_holds(const World& world) const;
  /// Whether the whole HashSurface stage may run at once now (see above),
  /// at the stage's start; `pool` sums its work under a work budget.
  bool surface_fits(const World& world, const Budget& budget, WorkerPool& pool) const;
  void query_batch(const World& world, const Budget& budget);
  std::size_t batch_size(std::size_t remaining, const Budget& budget) const;
  /// Starts a batch at the cursor (its size from batch_size(), for this
  /// step) and runs f over it on the pool; under a wall budget, also notes
  /// what an item took (m_batch_item_ms). The pool takes it in chunks of
  /// batch_chunk(size, threads, max_chunk) items.
  void run_batch(std::size_t remaining, std::size_t max_chunk, const World& world, const Budget& budget,
                 const WorkerPool::RangeFunction& f);
  bool depth_batch_allowed(const World& world);
  void depth_batch(const World& world, const Budget& budget);
  /// The penalty forces from the cursor on, ahead (into m_batch_forces).
  void forces_batch(const World& world, const Budget& budget);
  /// Without a budget and with no refresh due, a batch's answers may be
  /// taken without the loop's checks between tasks (each still counted).
  bool checks_decide_nothing(const World& world, const Budget& budget) const;

  CollisionSettings m_settings;
  DetectionMode m_mode;
  TaskGranularity m_granularity;
  WorkOrder m_order;
  bool m_widen_stale;
  bool m_rehash_stale;
  bool m_keep_table;
  double m_keep_table_rehash_share;
  bool m_table_kept = false;       // keep_table: the last tet hash completed, so the next cycle may refresh it
  bool m_opening_refresh = false;  // keep_table: the running refresh stands for the cycle's hash
  bool m_predict_tasks;
  bool m_whole_surface_hash;
  std::array<double, kCostStages> m_task_ms{};  // predict_tasks: recent task time per reported stage
  std::int64_t m_fresh_step = -1;  // rehash_stale: the step whose positions the tet table (or last refresh) holds
  std::int64_t m_hash_begin_step = -1;
  double m_tet_motion_m = 0.0;         // widen_stale: the uncapped motion bound behind m_tet_margin_m
  double m_motion_at_refresh_m = 0.0;  // m_tet_motion_m when the running refresh began
  bool m_refresh_wait = false;         // a refresh just ended: one task of the resumed stage first
  Stage m_resume_stage = Stage::Idle;  // what a refresh interrupted, and its cursor
  std::size_t m_resume_cursor = 0;
  double m_tet_margin_m = 0.0, m_surface_margin_m = 0.0;
  std::int64_t m_margin_step = 0;  // world.step_index the margins are up to date with
  std::vector<std::uint32_t> m_query_order;  // FastestFirst: indices into m_queries, fastest first
  CollisionPairs m_pairs;
  TetHashDetector m_detector;
  SurfaceHash m_surface;
  Stage m_stage = Stage::Idle;
  std::int64_t m_number = 0;
  std::size_t m_cursor = 0;
  std::size_t m_edge = 0;    // BorderDepth (fine): the current point's next neighbour
  BorderSum m_border_sum;    // and its sums so far
  std::int64_t m_tasks = 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> m_queries;    // (body, vertex) to query
  std::vector<std::int32_t> m_surface_bodies;                      // bodies whose surface is hashed
  std::size_t m_surface_body = 0;                                  // HashSurface's cursor: body, triangle
  std::vector<std::int32_t> m_layer_items;                         // contacts of the current layer
  std::vector<std::int32_t> m_layer_sources;                       // the layer before it (build_next_layer)
  std::int32_t m_layer = 0;
  std::vector<std::uint32_t> m_layer_mark;  // per contact: the scan that queued it
  std::uint32_t m_layer_scan = 0;
  std::size_t m_scan_cursor = 0;
  std::vector<Contact> m_contacts;
  ContactLookup m_lookup;
  StageCosts m_step_costs;
  ClockMs m_clock = steady_clock_ms();
  // settings.threads > 1 (spatial hash only): point queries answered ahead in
  // parallel batches, then consumed one a task in the serial order.
  // An answer is 16 bytes, its contact (if any) kept by the thread that
  // found it: the caller clears every answer and reads it back, the threads
  // write theirs, and with the contact inline (176 bytes an answer) that
  // traffic between the cores cost the 2-thread dog pair's query stage 14 %
  // (1.51 against 1.30 ms, paired medians; 1 in 10 queries hits).
  struct Answer {
    std::uint64_t work = 0;
    std::int32_t part = -1;   // the thread whose hits hold the contact; -1: none
    std::uint32_t index = 0;  // its place there
  };
  struct alignas(64) ThreadHits {  // aligned: the threads grow their own apart
    std::vector<Contact> hits;
  };
  const Contact& hit_of(const Answer& answer) const {
    return m_thread_hits[static_cast<std::size_t>(answer.part)].hits[answer.index];
  }
  void keep_hit(Answer& answer, int part, const Contact& contact) {
    std::vector<Contact>& hits = m_thread_hits[static_cast<std::size_t>(part)].hits;
    answer.part = part;
    answer.index = static_cast<std::uint32_t>(hits.size());
    hits.push_back(contact);
  }
  std::unique_ptr<WorkerPool> m_pool;
  std::vector<TetHashDetector::QueryScratch> m_thread_scratch;  // one per thread
  std::vector<ThreadHits> m_thread_hits;                        // one per thread: the batch's contacts
  std::vector<Answer> m_batch;          // answers for query positions [m_batch_begin, m_batch_begin + size)
  std::vector<Vec3> m_batch_forces;     // Forces: the batch's forces, beside its answers
  std::size_t m_batch_begin = 0;
  std::int64_t m_batch_step = -1;       // the step whose positions and tables they were computed at
  std::vector<SurfaceHash::QueryScratch> m_surface_scratch;  // [0] the serial path's; with a pool, one a thread
  std::vector<std::uint64_t> m_surface_work;  // the whole-stage surface hash: each triangle's work, in walk order
  std::int64_t m_whole_surface_hashes = 0;
  std::int64_t m_fresh_tet_hashes = 0;
  std::int64_t m_depth_check_step = -1;  // the step depth_batch_allowed() last decided at
  bool m_depth_batchable = false;
  std::array<double, kCostStages> m_batch_item_ms{};  // wall budgets: recent batch time per item, per stage
};

/// A batch's size under a wall budget: as many items as fit in `left_ms` at
/// `item_ms` each (the stage's recent time per item; <= 0: none measured
/// yet, then 4 a thread), at least one a thread, at most `most`.
std::size_t wall_batch_items(double left_ms, double item_ms, std::size_t threads, std::size_t most);

/// The most items a chunk of a batch takes: point queries and penalty
/// forces, mostly a few tens of nanoseconds each, and border depths, about a
/// microsecond each (dog pair).
inline constexpr std::size_t kQueryChunk = 128;
inline constexpr std::size_t kDepthChunk = 16;
inline constexpr std::size_t kForceChunk = 128;
/// How many items the pool's threads take at a time from a batch of `size`
/// items: a quarter of a thread's share, at least 16 (and at least one), at
/// most `max_chunk` (which wins over the 16).
std::size_t batch_chunk(std::size_t size, std::size_t threads, std::size_t max_chunk);

}  // namespace tcb
