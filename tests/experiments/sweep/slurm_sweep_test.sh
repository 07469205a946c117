#!/usr/bin/env bash
# A sweep on a real Slurm cluster (issue 15). The test stands up a single-node
# cluster of its own on localhost (munged, slurmctld and slurmd in the
# foreground, private key, private ports, private state; stopped on exit),
# writes the job array with `tcbench sweep --slurm 2`, submits it with sbatch,
# cancels array task 0 in the middle of its shard, resubmits that index alone,
# and checks that the merged DIR/summary.csv equals a local one-process
# sweep's, run for run: the same runs, each once, and every column that is not
# a wall-clock measurement identical (work budgets make them the same
# simulations).
# Exit 77 (ctest: skipped) with the reason when Slurm or munge is not
# installed, the test is not root (slurmd starts jobs as their user), or the
# daemons cannot start here.
# Usage: slurm_sweep_test.sh TCBENCH SWEEP_FILE WORK_DIR
set -euo pipefail
tcbench=$1 sweep=$2 work=$3
skip() { echo "SKIP: $*"; exit 77; }
fail() {
  echo "FAIL: $*" >&2
  for f in "$work"/cluster/slurm/*.out "$state"/log/*.log; do
    [[ -f $f ]] && { echo "--- $f (last lines)" >&2; tail -n 15 "$f" >&2; }
  done
  exit 1
}

for tool in munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (Debian slurm-wlm and munge; scripts/setup installs them)"
done
((EUID == 0)) || skip "slurmd must run as root to start jobs; this test runs as $(id -un)"

rm -rf "$work" && mkdir -p "$work"
# Daemon state outside WORK_DIR: a socket path must stay under 108 bytes.
state=$(mktemp -d /tmp/tcbench-slurm.XXXXXX)
chmod 755 "$state"  # munge clients need to reach the socket
mkdir -p "$state"/{log,ctld,spool}
pids=()
cleanup() {
  # Cancel whatever is left of our jobs before the daemons go, then stop them.
  [[ -f $state/slurm.conf ]] && SLURM_CONF=$state/slurm.conf scancel --quiet --full --user="$(id -un)" 2>/dev/null || true
  sleep 0.5
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$state"
}
trap cleanup EXIT

# Two free TCP ports next to each other (a port nothing answers on).
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
for ((try = 0; ; ++try)); do
  ((try < 50)) || skip "found no two free TCP ports on localhost"
  port=$((20000 + (RANDOM * 32768 + RANDOM + $$) % 40000))
  port_free "$port" && port_free $((port + 1)) && break
done
node=$(hostname -s)
cpus=$(nproc)

head -c 1024 /dev/urandom > "$state/munge.key"
chmod 600 "$state/munge.key"
munged --foreground --force --key-file="$state/munge.key" --socket="$state/munge.sock" \
  --pid-file="$state/munged.pid" --seed-file="$state/munge.seed" --log-file="$state/log/munged.log" \
  > "$state/log/munged.out" 2>&1 &
pids+=($!)

cat > "$state/slurm.conf" <<EOF
ClusterName=tcbenchtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$state/munge.sock
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$state/slurm.conf
for ((i = 0; i < 50; ++i)); do [[ -S $state/munge.sock ]] && break; sleep 0.1; done
[[ -S $state/munge.sock ]] || skip "munged did not start here: $(tail -n 3 "$state/log/munged.out")"
slurmctld -D -i > "$state/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D > "$state/log/slurmd.out" 2>&1 &
pids+=($!)
for ((i = 0; i < 300; ++i)); do
  [[ $(sinfo -h -o %T 2>/dev/null) == idle ]] && break
  sleep 0.1
done
[[ $(sinfo -h -o %T 2>/dev/null) == idle ]] ||
  skip "the Slurm daemons did not start here: $(tail -n 3 "$state"/log/*.out "$state"/log/slurm*.log 2>/dev/null | tr '\n' ' ')"
echo "cluster up: node $node, $cpus CPUs, ports $port/$((port + 1))"

# The reference: one process, the same sweep.
"$tcbench" sweep "$sweep" --out "$work/local" --jobs 2 --quiet

# The array script, then the array.
"$tcbench" sweep "$sweep" --out "$work/cluster" --slurm 2 --jobs 1
script=$work/cluster/sweep.sbatch
grep -q '^#SBATCH --array=0-1$' "$script" || fail "the script is not an array of 2: $(grep SBATCH "$script")"
job=$(sbatch --parsable "$script")
echo "submitted array job $job"

# Wait for a condition (a shell expression), at most $1 seconds.
wait_for() {
  local limit=$1 what=$2
  shift 2
  for ((i = 0; i < limit * 10; ++i)); do
    eval "$*" && return 0
    sleep 0.1
  done
  fail "waited ${limit}s for $what; queue: $(squeue -h 2>&1 | tr '\n' ' ')"
}
log0=$work/cluster/slurm/${job}_0.out
runs_ok() { local n; n=$(grep -c '^\[[0-9]*/[0-9]*\] ok' "$1" 2>/dev/null) || true; echo "${n:-0}"; }
task_state() { scontrol -o show job "${job}_$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2; }

# Cancel task 0 in mid-shard: once a run of it is complete, with more to come.
wait_for 120 "task 0 to complete its first run" '(( $(runs_ok "$log0") >= 1 ))'
shard_total=$(grep -o '^\[[0-9]*/[0-9]*\]' "$log0" | head -1 | cut -d/ -f2 | tr -d ']')
scancel "${job}_0"
wait_for 60 "task 0 to be cancelled" '[[ $(task_state 0) == CANCELLED ]]'
done_before=$(runs_ok "$log0")
((done_before < shard_total)) || fail "task 0 finished its $shard_total runs before the cancel landed"
partial=$(for d in "$work"/cluster/runs/*/; do [[ -f $d/run.json ]] || echo "$d"; done | wc -l)
echo "task 0 cancelled after $done_before of its $shard_total runs ($partial run folders without run.json)"
wait_for 300 "task 1 to finish" '[[ -z $(squeue -h -j "$job" 2>/dev/null) ]]'
[[ $(task_state 1) == COMPLETED ]] || fail "task 1 ended $(task_state 1)"
missing=$(grep -c ',missing,' "$work/cluster/summary.csv" || true)
((missing > 0)) || fail "summary.csv after the cancel lists no missing run"
echo "after the cancel: summary.csv lists $missing missing runs"

# Resubmit index 0 alone: its complete runs are skipped, the rest redone.
job2=$(sbatch --parsable --array=0 "$script")
wait_for 300 "the resubmitted task to finish" '[[ -z $(squeue -h -j "$job2" 2>/dev/null) ]]'
log_again=$work/cluster/slurm/${job2}_0.out
grep -q "$done_before skipped (complete)" "$log_again" ||
  fail "the resubmitted task did not skip the $done_before complete runs: $(tail -n 1 "$log_again")"
leftovers=$(find "$work/cluster" -name '*.tmp*' | head -3)
[[ -z $leftovers ]] || fail "partial files left: $leftovers"

# The merged summary against the one-process sweep's, run for run.
/usr/bin/python3 - "$work/local/summary.csv" "$work/cluster/summary.csv" <<'EOF' || fail "the merged summary differs from the local sweep's"
import csv, re, sys
# Wall-clock measurements (and the cores' handover ratios) differ between any two runs;
# everything else is the simulation's.
timing = re.compile(r"^wall_s$|_ms|ms_|_us$|^timing\.|overshoot|^handover_")
def rows(path):
    with open(path, newline="") as f:
        table = list(csv.DictReader(f))
    ids = [r["run"] for r in table]
    if len(ids) != len(set(ids)):
        sys.exit(f"{path}: a run appears twice")
    return {r["run"]: r for r in table}
local, cluster = rows(sys.argv[1]), rows(sys.argv[2])
if set(local) != set(cluster):
    sys.exit(f"different runs: only local {sorted(set(local) - set(cluster))}, only cluster {sorted(set(cluster) - set(local))}")
columns = [c for c in next(iter(local.values())) if not timing.search(c)]
if set(next(iter(cluster.values()))) != set(next(iter(local.values()))):
    sys.exit("different columns")
bad = [(run, c, local[run][c], cluster[run][c]) for run in local for c in columns if local[run][c] != cluster[run][c]]
for b in bad[:10]:
    print("differs:", *b, file=sys.stderr)
if bad:
    sys.exit(1)
statuses = {r["status"] for r in cluster.values()}
if statuses != {"ok"}:
    sys.exit(f"statuses {statuses}")
print(f"{len(local)} runs, {len(columns)} columns compared (not wall-clock): identical")
EOF
echo "ok: Slurm array of 2 shards, task 0 cancelled after $done_before runs and resubmitted; merged summary equals the local sweep's"
