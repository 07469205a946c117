// The sbatch script of `tcbench sweep --slurm N` (the cluster itself is
// exercised by slurm_sweep_test.sh).
#include "experiments/sweep/slurm_script.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "sim/io/atomic_file.hpp"

using namespace tcb;

TEST_CASE("slurm script: an array of N shards, each resuming into the shared DIR", "[sweep][fast]") {
  SlurmArraySettings s;
  s.executable = "/opt/tcbench/bin/tcbench";
  s.sweep_file = "/home/me/my sweep.toml";
  s.out_dir = "/shared/results/it's here";
  s.shards = 8;
  s.jobs = 2;
  s.provenance = "test";
  const std::string text = slurm_array_script(s);
  CHECK(text.rfind("#!/bin/bash\n", 0) == 0);
  CHECK(text.find("#SBATCH --array=0-7\n") != std::string::npos);
  CHECK(text.find("#SBATCH --cpus-per-task=2\n") != std::string::npos);
  CHECK(text.find("#SBATCH --output=/shared/results/it's here/slurm/%A_%a.out\n") != std::string::npos);
  CHECK(text.find("exec '/opt/tcbench/bin/tcbench' sweep '/home/me/my sweep.toml' --out '/shared/results/it'\\''s here' "
                  "--shard \"$SLURM_ARRAY_TASK_ID/8\" --resume --jobs 2\n") != std::string::npos);
  CHECK(text.find("--pin") == std::string::npos);
  s.pin = "auto";
  CHECK(slurm_array_script(s).find("--resume --jobs 2 --pin 'auto'\n") != std::string::npos);
}

TEST_CASE("shell_quote: what bash reads back is the text", "[sweep][fast]") {
  const std::string tricky = "a b'c\"d$e`f\\g\n!h*";
  CHECK(shell_quote("plain") == "'plain'");
  CHECK(shell_quote("") == "''");
  // Round trip through a real shell.
  const std::string file = "/tmp/tcbench_shell_quote_" + std::to_string(::getpid());
  const std::string command = "printf %s " + shell_quote(tricky) + " > " + file;
  REQUIRE(std::system(command.c_str()) == 0);
  CHECK(read_file(file) == tricky);
  std::remove(file.c_str());
}
