#!/usr/bin/env bash
# Kill and resume, many times (issue 15): a sweep is killed with SIGKILL
# (the whole process group: the sweep and its running children, as a
# cancelled job or a lost node would be) at KILLS pseudo-random moments,
# resumed with --resume after each, and then finished. Every run must then
# be present exactly once, no partial file may be left anywhere, and each run
# must be the same simulation as in an uninterrupted sweep (work budgets:
# its final energy, bit for bit).
# Usage: kill_resume_test.sh TCBENCH SWEEP_FILE WORK_DIR [KILLS]
set -euo pipefail
tcbench=$1 sweep=$2 work=$3 kills=${4:-10}
rm -rf "$work" && mkdir -p "$work"
set -m  # each background job in its own process group, so kill -- -PID reaches its children

"$tcbench" sweep "$sweep" --out "$work/reference" --jobs 2 --quiet
# The uninterrupted sweep's wall time sets the range the kills are drawn from.
start=$(date +%s%N)
"$tcbench" sweep "$sweep" --out "$work/timing" --jobs 2 --quiet
span_ms=$((($(date +%s%N) - start) / 1000000))
echo "uninterrupted sweep: ${span_ms} ms"

fail() { echo "FAIL: $*" >&2; exit 1; }
count() { find "$work/killed/runs" "$@" 2>/dev/null | wc -l || true; }  # 0 before the folder exists
# The finished sweep in $work/killed against the uninterrupted one.
verify() {
  [[ -s "$work/killed/summary.csv" ]] || fail "the finished sweep wrote no summary.csv"
  # No partial files: nothing written under a temporary name is left behind.
  leftovers=$(find "$work/killed" -name '*.tmp*' -o -name '*.partial' | head -5)
  [[ -z "$leftovers" ]] || fail "partial files left: $leftovers"
  # Every run exactly once, and the same runs as the reference.
  cut -d, -f1 "$work/reference/summary.csv" | tail -n +2 | sort > "$work/reference.ids"
  cut -d, -f1 "$work/killed/summary.csv" | tail -n +2 | sort > "$work/killed.ids"
  [[ $(sort -u "$work/killed.ids" | wc -l) == $(wc -l < "$work/killed.ids") ]] || fail "a run appears twice in summary.csv"
  diff "$work/reference.ids" "$work/killed.ids" >/dev/null || fail "the runs differ from the uninterrupted sweep's"
  [[ $(ls "$work/killed/runs" | wc -l) == $(wc -l < "$work/reference.ids") ]] || fail "run folders differ in number from the runs"
  [[ $(count -name run.json) == $(wc -l < "$work/reference.ids") ]] || fail "a run folder has no run.json"
  # The same simulations: status, steps and final energy of each run.
  column() { head -1 "$1" | tr , '\n' | grep -nx "$2" | cut -d: -f1; }
  pick() {
    local file=$1 cols=() name c
    for name in status steps energy.final_j; do
      c=$(column "$file" "$name") || true
      [[ -n "$c" ]] || fail "$file has no column $name"
      cols+=("$c")
    done
    cut -d, -f1,"${cols[0]}","${cols[1]}","${cols[2]}" "$file" | sort
  }
  pick "$work/reference/summary.csv" >/dev/null  # fails loudly on a missing column
  diff <(pick "$work/reference/summary.csv") <(pick "$work/killed/summary.csv") || fail "a resumed run differs from the uninterrupted one"
}

# Each kill comes at a random moment within what is left of the sweep (its
# uninterrupted span, scaled by the share of runs not yet complete), so the
# kills land all through it: in the middle of runs, between them, while the
# summary is written. A sweep that finishes first does not count as a kill;
# the loop goes on until KILLS have landed (at most 3 x KILLS tries).
total=$(($(wc -l < "$work/reference/summary.csv") - 1))
RANDOM=15  # the same kill moments on every run of the test
partial_seen=0 landed=0
for ((try = 1; landed < kills && try <= 3 * kills; ++try)); do
  complete=$(count -name run.json)
  left_ms=$((span_ms * (total - complete + 2) / total))  # + 2: at least a run or two of time
  delay_ms=$((50 + RANDOM % (left_ms + 1)))
  "$tcbench" sweep "$sweep" --out "$work/killed" --jobs 2 --quiet --resume &
  pid=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  if ! kill -9 -- "-$pid" 2>/dev/null; then
    wait "$pid" 2>/dev/null || true
    echo "try $try at ${delay_ms} ms: the sweep had finished; checked, starting over"
    verify
    rm -rf "$work/killed"
    continue
  fi
  wait "$pid" 2>/dev/null || true
  landed=$((landed + 1))
  folders=$(count -mindepth 1 -maxdepth 1 -type d)
  complete=$(count -name run.json)
  partial_seen=$((partial_seen + folders - complete))
  echo "kill $landed at ${delay_ms} ms: run folders $folders, with run.json $complete"
done
((landed == kills)) || { echo "FAIL: only $landed of $kills kills landed in a running sweep" >&2; exit 1; }
# A kill in the middle of a run leaves its folder without run.json: the path
# resume must clean up was taken.
((partial_seen > 0)) || { echo "FAIL: no kill landed inside a run" >&2; exit 1; }
"$tcbench" sweep "$sweep" --out "$work/killed" --jobs 2 --quiet --resume
verify
echo "ok: $kills kills, $total runs, each once, none partial, all equal to the uninterrupted sweep's"
