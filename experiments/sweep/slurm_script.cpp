#include "experiments/sweep/slurm_script.hpp"

#include <fmt/format.h>

namespace tcb {

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string slurm_array_script(const SlurmArraySettings& s) {
  const std::string dir = s.out_dir.string();
  std::string text = "#!/bin/bash\n";
  text += "# " + s.provenance + "\n";
  text += fmt::format(
      "# Submit:   sbatch {0}\n"
      "# Resubmit one shard (cancelled, timed out, node lost): sbatch --array=I {0}\n"
      "# Complete runs are skipped, half-written ones redone; the last shard to finish writes\n"
      "# {1}/summary.csv (or run the last line below with --shard 0/1 to rewrite it).\n",
      shell_quote((s.out_dir / "sweep.sbatch").string()), dir);
  text += "#SBATCH --job-name=" + s.job_name + "\n";
  text += fmt::format("#SBATCH --array=0-{}\n", s.shards - 1);
  text += fmt::format("#SBATCH --ntasks=1\n#SBATCH --cpus-per-task={}\n", s.jobs);
  // Slurm does not create the folder of --output, so the log folder is made
  // by `tcbench sweep --slurm`; %A is the array's job id, %a the index.
  text += "#SBATCH --output=" + (s.out_dir / "slurm" / "%A_%a.out").string() + "\n";
  text += "set -euo pipefail\n";
  text += fmt::format("exec {} sweep {} --out {} --shard \"$SLURM_ARRAY_TASK_ID/{}\" --resume --jobs {}{}\n",
                      shell_quote(s.executable.string()), shell_quote(s.sweep_file.string()), shell_quote(dir),
                      s.shards, s.jobs, s.pin.empty() ? "" : " --pin " + shell_quote(s.pin));
  return text;
}

}  // namespace tcb
