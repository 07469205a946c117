#pragma once
/// `tcbench sweep --slurm N`: the sbatch script of a Slurm job array that
/// runs a sweep as N shards into one shared result directory. Each array task
/// is `tcbench sweep FILE --out DIR --shard $SLURM_ARRAY_TASK_ID/N --resume`,
/// so a task that was cancelled, timed out or lost its node is finished by
/// resubmitting just that index (`sbatch --array=I DIR/sweep.sbatch`):
/// complete runs are skipped, half-written ones redone. Shards take the lock
/// of experiments/sweep/directory_lock.hpp to write summary.csv, so the last
/// task to finish leaves the complete one.

#include <cstddef>
#include <filesystem>
#include <string>

namespace tcb {

struct SlurmArraySettings {
  std::filesystem::path executable;  ///< absolute: array tasks start in the submission directory
  std::filesystem::path sweep_file;  ///< absolute
  std::filesystem::path out_dir;     ///< absolute, on a file system every node sees
  std::size_t shards = 1;            ///< array indices 0 .. shards-1
  std::size_t jobs = 1;              ///< runs at once per task = --cpus-per-task
  std::string pin;                   ///< passed on as --pin when not empty
  std::string job_name = "tcbench";
  std::string provenance;            ///< one comment line: which tcbench wrote it, when
};

/// The script's text. Paths are single-quoted for the shell.
std::string slurm_array_script(const SlurmArraySettings& settings);

/// `text` as one single-quoted shell word ('it'\''s').
std::string shell_quote(const std::string& text);

}  // namespace tcb
