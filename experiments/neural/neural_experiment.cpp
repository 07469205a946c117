#include "experiments/neural/neural_experiment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "experiments/metrics/distribution.hpp"
#include "experiments/neural/detector_scores.hpp"
#include "experiments/neural/finger_labeller.hpp"
#include "experiments/run/provenance.hpp"
#include "baselines/registry.hpp"
#include "method/handler/budget.hpp"
#include "method/handler/collision_settings.hpp"
#include "sim/world/world_desc.hpp"
#include "sim/io/atomic_file.hpp"

namespace tcb {
namespace {

using Clock = std::chrono::steady_clock;
using neural::Sample;

// The held-out codes come from their own seed and stream: no training seed
// ever draws them.
constexpr std::uint64_t kTestSeed = 0x7e57c0de, kTestStream = 100;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string cell(double x) { return std::isfinite(x) ? fmt::format("{}", x) : std::string(); }

// Median and mean of the finite values (NaN when none): a code whose
// reference distance is undefined (NaN) is left out, not counted as 0.
std::vector<double> finite_values(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  return v;
}

double median(const std::vector<double>& v) {
  const std::vector<double> f = finite_values(v);
  return f.empty() ? std::nan("") : summarize(f).p50;
}

double mean(const std::vector<double>& v) {
  const std::vector<double> f = finite_values(v);
  return f.empty() ? std::nan("") : summarize(f).mean;
}

// Distance from z0 to a collision-free code on the segment towards the rest
// code where the label changes (bisection with exact labels: a crossing, not
// necessarily the first) (the direct, detector-free
// answer a user could compute offline); NaN when the rest code collides.
double reference_distance(FingerLabeller& labeller, const Eigen::VectorXd& z0, const Eigen::VectorXd& rest, int bisections) {
  if (labeller(rest).collides) return std::nan("");
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < bisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (labeller(z0 + mid * (rest - z0)).collides ? lo : hi) = mid;
  }
  return hi * (rest - z0).norm();
}

// Runs job(index, worker) for every index in [0, count) on `workers`
// threads; a worker owns what it is handed (its labeller), so jobs never
// share mutable state, and each job's result lands in its own slot: the
// output does not depend on the thread count or the schedule.
template <class Job>
void parallel_jobs(std::size_t count, int workers, Job&& job) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> threads;
  for (int w = 0; w < std::max(1, workers); ++w)
    threads.emplace_back([&, w] {
      for (std::size_t i = next++; i < count; i = next++) {
        try {
          job(i, w);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(error_mutex);
          if (!error) error = std::current_exception();
          next = count;  // hand out no more jobs: the first error ends the experiment
        }
      }
    });
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

// What exact self-collision handling costs on the same poses: the `full`
// method's step (hash, detection, depth, response; self-collision on) on
// decode(z) for each code, median milliseconds, and the mean number of
// colliding points it found. The detector's cost is one network evaluation
// whatever the mesh; this is what it replaces.
struct FullCost {
  double step_ms_median = std::nan("");
  double colliding_points_mean = std::nan("");
};

FullCost full_handling_cost(const SkinnedFinger& finger, const std::vector<Sample>& codes) {
  const SkinnedFingerDesc& d = finger.desc();
  WorldDesc desc;
  desc.gravity_m_per_s2 = Vec3::Zero();
  ObjectDesc object;
  object.name = "finger";
  object.mesh = fmt::format("box:size={}x{}x{},cells={}x{}x{}", d.size_m.x(), d.size_m.y(), d.size_m.z(), d.cells[0],
                            d.cells[1], d.cells[2]);
  object.self_collision = true;
  desc.objects.push_back(object);
  World world = build_world(desc);
  Body& body = world.bodies.front();
  // The same box, with the bones as parts: the generator and the finger
  // number its vertices alike, which holds because desc.mesh_order is the
  // file's (a "curve" desc would renumber the generated box only).
  body.mesh = finger.mesh();
  const CollisionSettings settings = resolve_collision_settings(world, CollisionDesc{}, desc.dt_s);
  const auto handler = make_handler("full");
  handler->init(world, settings);
  std::vector<double> ms;
  double points = 0.0;
  for (const Sample& code : codes) {
    body.x_m = finger.decode(code.z);
    std::fill(body.v_m_per_s.begin(), body.v_m_per_s.end(), Vec3::Zero());
    std::fill(body.contact_force_n.begin(), body.contact_force_n.end(), Vec3::Zero());
    world.contact_links.clear();
    Budget unlimited = Budget::unlimited();
    const auto start = Clock::now();
    const StepReport report = handler->step(world, unlimited);
    ms.push_back(seconds_since(start) * 1e3);
    points += static_cast<double>(report.colliding_points);
  }
  return {median(ms), codes.empty() ? std::nan("") : points / static_cast<double>(codes.size())};
}

struct Trained {
  neural::Strategy strategy;
  std::uint64_t seed;
  neural::Mlp<double> net;
};

}  // namespace

NeuralExperimentSettings neural_experiment_defaults(bool quick) {
  NeuralExperimentSettings s;
  s.learning.layers = {0, 64, 64, 64, 1};
  s.learning.activation = neural::Activation::Tanh;
  s.presets = {"finger_small", "finger_large"};  // two resolutions: the detector's cost must not follow the mesh
  if (quick) {
    s.presets = {"finger_small"};
    s.seeds = {1, 2};
    s.test_codes = 600;
    s.learning.bootstrap_labels = 100;
    s.learning.bootstrap_steps = 400;
    s.learning.rounds = 4;
    s.learning.labels_per_round = 50;
    s.learning.steps_per_round = 200;
    s.alm_codes = 20;
    s.alm_margins = {0.0, 2.0};
  }
  return s;
}

void run_neural_experiment(const NeuralExperimentSettings& settings) {
  std::mutex say_mutex;  // workers report progress too
  const auto say = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(say_mutex);
    if (settings.progress) settings.progress(line);
  };
  const auto wall_start = Clock::now();
  std::ostringstream learning, alm;
  learning << "preset,strategy,seed,labels,gradient_steps,test_codes,accuracy,fnr,fpr,precision,recall\n";
  alm << "preset,strategy,seed,margin,attempted,network_feasible,resolved,resolved_share,median_distance,"
         "mean_distance,median_reference_distance,median_distance_ratio,mean_evaluations\n";
  nlohmann::ordered_json presets = nlohmann::ordered_json::array();
  for (const std::string& preset : settings.presets) {
    const SkinnedFinger finger(finger_preset(preset));
    const int workers = std::max(1, settings.jobs);
    std::vector<std::unique_ptr<FingerLabeller>> labellers;
    for (int w = 0; w < workers; ++w) labellers.push_back(std::make_unique<FingerLabeller>(finger));
    const auto label_seconds = [&] {
      double t = 0.0;
      for (const auto& l : labellers) t += l->seconds();
      return t;
    };
    const auto label_count = [&] {
      std::int64_t n = 0;
      for (const auto& l : labellers) n += l->labels();
      return n;
    };
    const int n = finger.latent_size();
    neural::LearningSettings learning_settings = settings.learning;
    learning_settings.layers.front() = n;

    say(fmt::format("{}: labelling {} held-out codes", preset, settings.test_codes));
    std::vector<Sample> test_set(static_cast<std::size_t>(std::max(0, settings.test_codes)));
    parallel_jobs(test_set.size(), workers, [&](std::size_t i, int w) {
      test_set[i].z = neural::uniform_code(n, kTestSeed, kTestStream, i);
      test_set[i].label = (*labellers[static_cast<std::size_t>(w)])(test_set[i].z);
    });
    std::int64_t colliding = 0;
    for (const Sample& x : test_set) colliding += x.label.collides;
    const double test_label_seconds = label_seconds();

    // Every (strategy, seed) is one job; its rows and network go to its slot.
    struct Job {
      neural::Strategy strategy;
      std::uint64_t seed;
      std::string rows;
      neural::Mlp<double> net;
      double train_seconds = 0.0;
    };
    std::vector<Job> jobs;
    for (const neural::Strategy strategy : {neural::Strategy::Supervised, neural::Strategy::Active})
      for (const std::uint64_t seed : settings.seeds) jobs.push_back({strategy, seed, {}, {}, 0.0});
    const double labels_before = label_seconds();
    const std::int64_t count_before = label_count();
    parallel_jobs(jobs.size(), workers, [&](std::size_t j, int w) {
      Job& job = jobs[j];
      FingerLabeller& labeller = *labellers[static_cast<std::size_t>(w)];
      say(fmt::format("{}: {} learning, seed {}", preset, neural::strategy_name(job.strategy), job.seed));
      const double own_labels_before = labeller.seconds();
      const auto start = Clock::now();
      job.net = neural::learn(
          job.strategy, std::ref(labeller), learning_settings, job.seed,
          [&](const neural::Mlp<double>& current, int labels, int steps) {
            const DetectorScores sc = score_detector(current, test_set);
            job.rows += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", preset, neural::strategy_name(job.strategy),
                                    job.seed, labels, steps, test_set.size(), cell(sc.accuracy()),
                                    cell(sc.false_negative_rate()), cell(sc.false_positive_rate()),
                                    cell(sc.precision()), cell(sc.recall()));
          });
      job.train_seconds = seconds_since(start) - (labeller.seconds() - own_labels_before);
    });
    double train_seconds = 0.0;
    for (const Job& job : jobs) learning << job.rows, train_seconds += job.train_seconds;
    const double learn_label_seconds = label_seconds() - labels_before;
    const std::int64_t learn_labels = label_count() - count_before;

    // ALM on the first colliding held-out codes.
    std::vector<Eigen::VectorXd> starts;
    for (const Sample& x : test_set)
      if (x.label.collides && static_cast<int>(starts.size()) < settings.alm_codes) starts.push_back(x.z);
    say(fmt::format("{}: reference distances for {} colliding codes", preset, starts.size()));
    std::vector<double> reference(starts.size());
    parallel_jobs(starts.size(), workers, [&](std::size_t i, int w) {
      reference[i] = reference_distance(*labellers[static_cast<std::size_t>(w)], starts[i], finger.rest_code(),
                                        settings.reference_bisections);
    });
    say(fmt::format("{}: ALM with {} networks at {} margins", preset, jobs.size(), settings.alm_margins.size()));
    const std::size_t margins = settings.alm_margins.size();
    std::vector<std::string> alm_rows(jobs.size() * margins);
    std::vector<double> alm_job_seconds(alm_rows.size(), 0.0);
    parallel_jobs(alm_rows.size(), workers, [&](std::size_t k, int w) {
      const Job& t = jobs[k / margins];
      const double margin = settings.alm_margins[k % margins];
      FingerLabeller& labeller = *labellers[static_cast<std::size_t>(w)];
      const neural::Constraint constraint = [&](const Eigen::VectorXd& z, Eigen::VectorXd& grad) {
        return t.net.value_and_input_gradient(z, grad) + margin;
      };
      std::int64_t feasible = 0, resolved = 0;
      std::vector<double> distance, ratio, evaluations;
      for (std::size_t i = 0; i < starts.size(); ++i) {
        const auto start = Clock::now();
        neural::AlmState state = neural::alm_start(starts[i], settings.alm);
        Budget unlimited = Budget::unlimited();
        neural::alm_resume(state, constraint, settings.alm, unlimited);
        alm_job_seconds[k] += seconds_since(start);
        feasible += state.c <= settings.alm.feasibility_tolerance;
        resolved += !labeller(state.z).collides;
        distance.push_back((state.z - starts[i]).norm());
        ratio.push_back(distance.back() / reference[i]);
        evaluations.push_back(static_cast<double>(state.evaluations));
      }
      const double attempted = static_cast<double>(starts.size());
      alm_rows[k] = fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", preset, neural::strategy_name(t.strategy),
                                t.seed, margin, starts.size(), feasible, resolved,
                                cell(starts.empty() ? std::nan("") : static_cast<double>(resolved) / attempted),
                                cell(median(distance)), cell(mean(distance)), cell(median(reference)),
                                cell(median(ratio)), cell(mean(evaluations)));
    });
    double alm_seconds = 0.0;
    for (std::size_t k = 0; k < alm_rows.size(); ++k) alm << alm_rows[k], alm_seconds += alm_job_seconds[k];
    std::vector<Trained> trained;
    for (Job& job : jobs) trained.push_back({job.strategy, job.seed, std::move(job.net)});

    // One detector evaluation (forward + input gradient): the constant-time
    // step the network offers, whatever the mesh size.
    std::vector<double> eval_us;
    {
      Eigen::VectorXd grad;
      double sink = 0.0;
      for (int rep = 0; rep < 21; ++rep) {
        const auto start = Clock::now();
        for (int k = 0; k < 200; ++k) sink += trained.front().net.value_and_input_gradient(test_set[static_cast<std::size_t>(k) % test_set.size()].z, grad);
        eval_us.push_back(seconds_since(start) * 1e6 / 200.0);
      }
      if (!std::isfinite(sink)) eval_us.assign(1, std::nan(""));
    }
    // Exact handling on the first held-out codes, for the same poses.
    say(fmt::format("{}: the full method's step on {} held-out poses", preset, std::min<std::size_t>(test_set.size(), 200)));
    const FullCost full = full_handling_cost(
        finger, std::vector<Sample>(test_set.begin(), test_set.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(test_set.size(), 200))));
    nlohmann::ordered_json p;
    p["preset"] = preset;
    p["vertices"] = finger.mesh()->positions_m.size();
    p["tets"] = finger.mesh()->tet_count();
    p["latent_size"] = n;
    p["layers"] = learning_settings.layers;
    p["test_codes"] = test_set.size();
    p["test_colliding"] = colliding;
    p["label_ms_per_code"] = 1e3 * test_label_seconds / std::max<double>(1.0, static_cast<double>(test_set.size()));
    p["learning_labels"] = learn_labels;
    p["learning_label_seconds"] = learn_label_seconds;
    p["training_seconds"] = train_seconds;
    p["alm_seconds"] = alm_seconds;
    p["detector_eval_us_median"] = median(eval_us);
    p["alm_codes"] = starts.size();
    p["full_step_ms_median"] = full.step_ms_median;
    p["full_colliding_points_mean"] = full.colliding_points_mean;
    presets.push_back(p);
  }
  nlohmann::ordered_json meta;
  meta["experiment"] = "neural self-collision detector (seed 002)";
  meta["command"] = settings.command_line;
  meta["created"] = utc_timestamp();
  meta["build"] = build_info();
  meta["machine"] = machine_info();
  meta["seeds"] = settings.seeds;
  meta["hidden_layers"] = std::vector<int>(settings.learning.layers.begin() + 1, settings.learning.layers.end() - 1);
  meta["activation"] = settings.learning.activation == neural::Activation::Tanh ? "tanh" : "celu";
  meta["bootstrap_labels"] = settings.learning.bootstrap_labels;
  meta["bootstrap_steps"] = settings.learning.bootstrap_steps;
  meta["rounds"] = settings.learning.rounds;
  meta["labels_per_round"] = settings.learning.labels_per_round;
  meta["steps_per_round"] = settings.learning.steps_per_round;
  meta["exploration_share"] = settings.learning.exploration_share;
  meta["alm_margins"] = settings.alm_margins;
  meta["jobs"] = settings.jobs;
  meta["presets"] = presets;
  meta["wall_seconds"] = seconds_since(wall_start);
  std::filesystem::create_directories(settings.out);
  write_file_atomically(settings.out / "learning.csv", learning.str());
  write_file_atomically(settings.out / "alm.csv", alm.str());
  write_file_atomically(settings.out / "neural.json", meta.dump(2) + "\n");
}

bool neural_results_match(const std::filesystem::path& neural_json, const NeuralExperimentSettings& wanted) {
  try {
    const auto meta = nlohmann::json::parse(read_file(neural_json));
    std::vector<std::string> presets;
    for (const auto& p : meta.at("presets")) presets.push_back(p.at("preset").get<std::string>());
    const neural::LearningSettings& l = wanted.learning;
    bool same_codes = true;
    for (const auto& p : meta.at("presets")) same_codes = same_codes && p.at("test_codes").get<int>() == wanted.test_codes;
    return meta.at("seeds").get<std::vector<std::uint64_t>>() == wanted.seeds && presets == wanted.presets &&
           same_codes && meta.at("bootstrap_labels").get<int>() == l.bootstrap_labels &&
           meta.at("bootstrap_steps").get<int>() == l.bootstrap_steps && meta.at("rounds").get<int>() == l.rounds &&
           meta.at("labels_per_round").get<int>() == l.labels_per_round &&
           meta.at("steps_per_round").get<int>() == l.steps_per_round &&
           meta.at("alm_margins").get<std::vector<double>>() == wanted.alm_margins;
  } catch (const std::exception&) {
    return false;  // missing, unreadable or not ours: run it again
  }
}

}  // namespace tcb
