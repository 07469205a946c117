// tcbench neural experiment [--out DIR] [--quick] [--preset P]... [--seeds N]:
// the neural self-collision detector of seed 002 on the skinned finger
// (experiments/neural/neural_experiment.hpp says what it writes).
#include <fmt/format.h>

#include <iostream>

#include "experiments/cli/command.hpp"
#include "experiments/cli/option_checks.hpp"
#include "experiments/neural/code_labels.hpp"
#include "experiments/neural/finger_labeller.hpp"
#include "experiments/neural/neural_experiment.hpp"
#include "experiments/neural/path_resolution.hpp"
#include "experiments/neural/train_detector.hpp"
#include "sim/io/input_error.hpp"
#include "sim/latent/skinned_finger.hpp"

namespace tcb::cli {
namespace {

// Where a command will write, checked before its work (minutes of labelling
// or training) rather than after it: exit 2 naming the option.
void check_output_file(const std::string& file, const char* option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(file);
  if (fs::is_directory(path, ec)) throw InputError(option, 0, "'" + file + "' is a directory, not a file to write");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(dir, ec)) throw InputError(option, 0, "no directory '" + dir.string() + "' to write '" + file + "' into");
}

void make_output_dir(const std::string& dir, const char* option) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(option, 0, "cannot make the directory '" + dir + "'" + (ec ? ": " + ec.message() : std::string()));
}

class NeuralCommand final : public Command {
 public:
  explicit NeuralCommand(CLI::App& parent) {
    app = parent.add_subcommand("neural", "The neural self-collision detector (seed 002, N-Penetrate)");
    app->require_subcommand(1);
    m_experiment = app->add_subcommand(
        "experiment", "Active vs supervised learning with exact labels, then ALM resolution judged by the oracle");
    m_experiment->footer(
        "Writes DIR/learning.csv (accuracy, FNR, FPR, precision, recall on held-out codes against labels\n"
        "spent, per strategy and seed), DIR/alm.csv (collisions the ALM resolves, by margin, with the\n"
        "distance moved and the oracle's reference distance) and DIR/neural.json (settings, build,\n"
        "machine, label and training cost). Presets: finger_small, finger_large.\n"
        "Exit status: 0 written; 2 bad input.");
    m_experiment->add_option("--out", m_out, "Result directory")->check(non_empty_path())->capture_default_str();
    m_experiment->add_flag("--quick", m_quick, "Fewer seeds, labels and codes (a smoke run of about a minute)");
    m_experiment->add_option("--preset", m_presets, "Latent families to run (repeatable; default: finger_small and finger_large, --quick: finger_small)");
    m_experiment->add_option("--seeds", m_seed_count, "Training seeds 1..N (default: 3, --quick 2)")
        ->transform(whole_number(1, 100));
    m_experiment->add_option("--rounds", m_rounds, "Learning rounds after the bootstrap (default 8, --quick 4)")
        ->transform(whole_number(0, 10000));
    m_experiment->add_option("--labels-per-round", m_labels_per_round, "Labels each round adds (default 100, --quick 50)")
        ->transform(whole_number(1, 1000000));
    m_experiment->add_option("--steps-per-round", m_steps_per_round, "Adam steps each round (default 500, --quick 200)")
        ->transform(whole_number(0, 100000000));
    m_experiment->add_option("--test-codes", m_test_codes, "Held-out codes (default 2000, --quick 600)")
        ->transform(whole_number(1, 10000000));
    m_experiment->add_option("--jobs", m_jobs, "Worker threads (the results do not depend on it)")
        ->transform(whole_number(1, 64))
        ->capture_default_str();
    m_experiment->add_flag("--quiet", m_quiet, "No progress lines");

    m_train = app->add_subcommand("train", "Train one detector for a latent family and save it for --method neural");
    m_train->footer(
        "Writes MODEL (the network as JSON, with how it was trained: preset, strategy, seed, labels,\n"
        "gradient steps, cost, build, machine). A scene names it as an object's latent_model.\n"
        "The same options give the same network, bit for bit, on one build.\n"
        "Exit status: 0 written; 2 bad input.");
    m_train->add_option("--out", m_model, "The model file to write (.json)")->check(non_empty_path())->required();
    m_train->add_option("--preset", m_train_preset, "Latent family: finger_small or finger_large")->capture_default_str();
    m_train->add_option("--strategy", m_strategy, "active (samples pulled to the decision boundary) or supervised (uniform)")
        ->check(CLI::IsMember({"active", "supervised"}))
        ->capture_default_str();
    m_train->add_option("--seed", m_train_seed, "Training seed")->transform(whole_number(0, 1000000000))->capture_default_str();
    m_train->add_option("--rounds", m_rounds, "Learning rounds after the bootstrap (default 8)")->transform(whole_number(0, 10000));
    m_train->add_option("--labels-per-round", m_labels_per_round, "Labels each round adds (default 100)")
        ->transform(whole_number(1, 1000000));
    m_train->add_option("--steps-per-round", m_steps_per_round, "Adam steps each round (default 500)")
        ->transform(whole_number(0, 100000000));
    m_train->add_flag("--quiet", m_quiet, "No progress lines");

    m_gen = app->add_subcommand("gen", "Write uniformly drawn codes with their exact labels (a data set for your own detector)");
    m_gen->footer(
        "Writes OUT.csv: z0..z11, collides (the oracle: some vertex inside tets of a part outside its own\n"
        "neighbourhood), pd_m (the largest true vertex depth, m). The same --seed gives the same codes.\n"
        "Exit status: 0 written; 2 bad input.");
    m_gen->add_option("--out", m_gen_out, "The CSV file to write")->check(non_empty_path())->required();
    m_gen->add_option("--preset", m_gen_preset, "Latent family: finger_small or finger_large")->capture_default_str();
    m_gen->add_option("--codes", m_gen_codes, "How many codes")->transform(whole_number(1, 100000000))->capture_default_str();
    m_gen->add_option("--seed", m_gen_seed, "Seed of the draw")->transform(whole_number(0, 1000000000))->capture_default_str();

    m_alm = app->add_subcommand("alm", "Resolve the colliding frames of a latent path with the ALM, under a work budget per step");
    m_alm->footer(
        "For each code of the path: the network's logit and the oracle's verdict; where the network says\n"
        "colliding, the ALM (min |z - z0|^2 subject to logit + margin <= 0) runs --budget-work network\n"
        "evaluations a step, resumed until done, and the oracle judges its answer. Writes OUT.csv, one row\n"
        "per path sample (time_s, logit, network_collides, oracle_collides, oracle_pd_m, alm_steps,\n"
        "alm_evaluations, alm_feasible, alm_converged, distance, resolved).\n"
        "Example: tcbench neural alm --model experiments/scenes/finger_small_active.json\n"
        "           --path experiments/scenes/finger_curl_path.csv --budget-work 20 --out alm_path.csv\n"
        "Exit status: 0 written; 2 bad input.");
    m_alm->add_option("--model", m_alm_model, "The network (tcbench neural train)")->required();
    m_alm->add_option("--path", m_alm_path, "A latent path CSV (time_s,z0,...)")->required();
    m_alm->add_option("--out", m_alm_out, "The CSV file to write")->check(non_empty_path())->required();
    m_alm->add_option("--preset", m_alm_preset, "The model's latent family")->capture_default_str();
    m_alm->add_option("--margin", m_alm_margin, "Constraint margin in logits: logit + margin <= 0")
        ->transform(decimal_number(-100.0, 100.0))
        ->capture_default_str();
    m_alm->add_option("--budget-work", m_alm_work, "Network evaluations per step (0: unlimited, one step)")
        ->transform(whole_number(0, 1000000000))
        ->capture_default_str();
  }

  int execute() override {
    if (m_train->parsed()) return train();
    if (m_gen->parsed()) {
      check_output_file(m_gen_out, "--out");
      const CodeLabelCounts c = label_uniform_codes(m_gen_preset, m_gen_codes, static_cast<std::uint64_t>(m_gen_seed), m_gen_out);
      std::cout << fmt::format("wrote {}: {} {} codes, {} colliding, labels {:.2f} ms/code\n", m_gen_out, c.codes,
                               m_gen_preset, c.colliding, 1e3 * c.label_seconds / static_cast<double>(c.codes));
      return 0;
    }
    if (m_alm->parsed()) return alm();
    NeuralExperimentSettings s = neural_experiment_defaults(m_quick);
    for (const std::string& p : m_presets) (void)finger_preset_option(p);
    if (!m_presets.empty()) s.presets = m_presets;
    if (m_seed_count > 0) {
      s.seeds.clear();
      for (int k = 1; k <= m_seed_count; ++k) s.seeds.push_back(static_cast<std::uint64_t>(k));
    }
    if (m_rounds >= 0) s.learning.rounds = m_rounds;
    if (m_labels_per_round > 0) s.learning.labels_per_round = m_labels_per_round;
    if (m_steps_per_round >= 0) s.learning.steps_per_round = m_steps_per_round;
    if (m_test_codes > 0) s.test_codes = m_test_codes;
    make_output_dir(m_out, "--out");
    s.out = m_out;
    s.jobs = m_jobs;
    s.command_line = argv;
    if (!m_quiet) s.progress = [](const std::string& line) { std::cerr << "neural: " << line << '\n'; };
    run_neural_experiment(s);
    std::cout << fmt::format("wrote {}/learning.csv, alm.csv, neural.json\n", m_out);
    return 0;
  }

 private:
  int train() {
    check_output_file(m_model, "--out");
    TrainDetectorSettings s = train_detector_defaults();
    (void)finger_preset_option(m_train_preset);
    s.preset = m_train_preset;
    s.strategy = m_strategy == "active" ? neural::Strategy::Active : neural::Strategy::Supervised;
    s.seed = static_cast<std::uint64_t>(m_train_seed);
    if (m_rounds >= 0) s.learning.rounds = m_rounds;
    if (m_labels_per_round > 0) s.learning.labels_per_round = m_labels_per_round;
    if (m_steps_per_round >= 0) s.learning.steps_per_round = m_steps_per_round;
    s.out = m_model;
    s.command_line = argv;
    if (!m_quiet) s.progress = [](const std::string& line) { std::cerr << "neural train: " << line << '\n'; };
    const TrainedDetector t = train_detector(s);
    std::cout << fmt::format("wrote {}: {} {} network, {} labels ({:.1f} s), {} gradient steps ({:.1f} s)\n", m_model,
                             m_train_preset, m_strategy, t.labels, t.label_seconds, t.gradient_steps, t.train_seconds);
    return 0;
  }

  int alm() {
    check_output_file(m_alm_out, "--out");
    PathResolutionSettings s;
    s.preset = m_alm_preset;
    s.model = m_alm_model;
    s.path = m_alm_path;
    s.out = m_alm_out;
    s.margin = m_alm_margin;
    s.work_per_step = static_cast<std::uint64_t>(m_alm_work);
    const PathResolution r = resolve_path(s);
    std::cout << fmt::format(
        "wrote {}: {} frames; the network says colliding on {} (the oracle on {}, both on {}); the ALM resolved {} "
        "of {} (oracle-checked), median distance {:.3g}, longest {} step(s) at {} evaluations a step{}\n",
        m_alm_out, r.frames, r.network_colliding, r.oracle_colliding, r.true_positives, r.resolved, r.network_colliding,
        r.distance_median, r.steps_max, m_alm_work == 0 ? std::string("unlimited") : std::to_string(m_alm_work),
        r.abandoned ? fmt::format(", {} abandoned", r.abandoned) : std::string());
    return 0;
  }

  CLI::App* m_experiment = nullptr;
  CLI::App* m_train = nullptr;
  CLI::App* m_gen = nullptr;
  CLI::App* m_alm = nullptr;
  std::string m_gen_out, m_gen_preset = "finger_small";
  std::int64_t m_gen_codes = 1000;
  int m_gen_seed = 1;
  std::string m_alm_model, m_alm_path, m_alm_out, m_alm_preset = "finger_small";
  double m_alm_margin = 0.0;
  std::int64_t m_alm_work = 0;
  std::string m_model, m_train_preset = "finger_small", m_strategy = "active";
  int m_train_seed = 1;
  std::string m_out = "neural_results";
  bool m_quick = false, m_quiet = false;
  std::vector<std::string> m_presets;
  int m_seed_count = 0;
  int m_jobs = 2;
  int m_rounds = -1, m_labels_per_round = 0, m_steps_per_round = -1, m_test_codes = 0;
};

}  // namespace

std::unique_ptr<Command> make_neural_command(CLI::App& parent) { return std::make_unique<NeuralCommand>(parent); }

}  // namespace tcb::cli
