#!/usr/bin/env bash
# A second simulator on one bus is refused (docs/physics.md, "One physics per
# bus"; docs/failures.md), on one network namespace's LCM ($LCM_DEFAULT_URL):
#   1. a second ubersim_physics on the first one's URL exits 1 before it steps,
#      with one line naming the first's pid and --lcm-url / --channel-prefix;
#      the first keeps stepping, alone on the bus (SIM_STATE from one world);
#   2. on another port, or with a channel prefix, a second physics runs beside it;
#   3. the claim goes with its process: after the first is killed (SIGKILL)
#      a physics on its URL starts;
#   4. tools/launch.sh started while a physics runs on its bus says that line
#      and exits 1 before it starts anything (no log folder, no process);
#   5. of two tools/launch.sh started at one instant one runs, the other exits 1
#      naming the first's physics, and starts no emulator.
# Usage: test_second_start.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build)
set -uo pipefail
source_dir=$1
bin=${UBERSIM_BUILD_DIR:-$source_dir/build}/bin
work=$(mktemp -d "${TMPDIR:-/tmp}/second-start-XXXXXX")
url=${LCM_DEFAULT_URL:?run through tests/run_isolated.sh}
port=${url#*://*:}
port=${port%%\?*}
other_url=${url/:$port/:$((port + 1))}
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"
started=()
cleanup() {
  local pid
  for pid in "${started[@]}"; do kill -KILL "$pid" 2>/dev/null; done
}
trap cleanup EXIT

# physics NAME ARGS...: starts a physics in the background, its pid in $!.
physics() {
  local name=$1
  shift
  "$bin/ubersim_physics" --scenario field2002_5v5 "$@" >"$work/$name.out" 2>"$work/$name.err" &
  started+=($!)
}
# sim_time URL: the sim time physics on URL reports (ubersim_referee ping), or "".
sim_time() {
  timeout 10 "$bin/ubersim_referee" --lcm-url "$1" ping 2>/dev/null | grep -oE 'sim time [0-9.]+' | head -1 | cut -d' ' -f3
}
# still_running PID WHAT: the process has not exited.
still_running() { kill -0 "$1" 2>/dev/null || fail "$2 is not running: $(cat "$work"/*.err | tail -n 5)"; }

physics first
first=$!
sleep 1.5
still_running "$first" "the first physics"
before=$(sim_time "$url")
[ -n "$before" ] || fail "the first physics does not answer ping"

# 1. The second on the same URL.
start_ns=$(date +%s%N)
physics second
second=$!
# It must stop by itself, at once; one that runs on is a failure, not a hang.
for _ in $(seq 100); do kill -0 "$second" 2>/dev/null || break; sleep 0.1; done
kill -0 "$second" 2>/dev/null && { fail "the second physics still runs after 10 s"; kill -KILL "$second"; }
wait "$second"
status=$?
echo "second physics on $url -> exit $status in $((($(date +%s%N) - start_ns) / 1000000)) ms: $(cat "$work/second.err")"
[ "$status" = 1 ] || fail "second physics: exit $status, expected 1"
[ "$(wc -l <"$work/second.err")" = 1 ] || fail "second physics: not one line on stderr"
grep -q "another ubersim_physics (pid $first) already runs on LCM port $port" "$work/second.err" ||
  fail "second physics: the line does not name the first's pid $first"
grep -q -- "--lcm-url udpm://.*:$((port + 1))" "$work/second.err" || fail "second physics: no --lcm-url to run beside it"
grep -q -- "--channel-prefix" "$work/second.err" || fail "second physics: no --channel-prefix to run beside it"
[ -s "$work/second.out" ] && fail "second physics printed on stdout: $(head -c 300 "$work/second.out")"
sleep 1
still_running "$first" "the first physics (after the second start)"
after=$(sim_time "$url")
echo "the first physics: sim time $before s before the second start, $after s after"
awk -v a="$after" -v b="$before" 'BEGIN { exit !(a > b) }' || fail "the first physics stopped stepping ($before -> $after)"
# --check-bus says the same and starts nothing.
"$bin/ubersim_physics" --check-bus 2>"$work/check.err"
status=$?
[ "$status" = 1 ] && grep -q "(pid $first)" "$work/check.err" || fail "--check-bus: exit $status: $(cat "$work/check.err")"

# 2. Beside it: another port, a channel prefix.
physics other_port --lcm-url "$other_url"
other_port=$!
physics prefixed --channel-prefix beside_
prefixed=$!
sleep 2
still_running "$other_port" "physics on $other_url"
still_running "$prefixed" "physics with --channel-prefix beside_"
[ -n "$(sim_time "$other_url")" ] || fail "physics on $other_url does not answer ping"
still_running "$first" "the first physics (with two beside it)"
for pid in "$other_port" "$prefixed"; do
  kill -TERM "$pid"
  wait "$pid" || fail "a physics beside the first did not stop cleanly"
done

# 4. launch.sh while the first runs: refused before anything starts.
timeout 30 "$source_dir/tools/launch.sh" --log-dir "$work/launch-logs" >"$work/launch.out" 2>"$work/launch.err" </dev/null
status=$?
echo "launch.sh beside the first -> exit $status: $(cat "$work/launch.err")"
[ "$status" = 1 ] || fail "launch.sh: exit $status, expected 1"
[ "$(wc -l <"$work/launch.err")" = 1 ] || fail "launch.sh: not one line on stderr"
grep -q "^launch: ubersim_physics: another ubersim_physics (pid $first)" "$work/launch.err" ||
  fail "launch.sh: the line does not name the first's pid"
[ -e "$work/launch-logs" ] && fail "launch.sh made its log folder (started?)"
still_running "$first" "the first physics (after launch.sh)"
# With the SSL bridge (where it is built), the line also names the option for other SSL ports.
if [ -x "$bin/ubersim_ssl_bridge" ] && [ -x "$bin/ubersim_viewer" ]; then
  timeout 30 "$source_dir/tools/launch.sh" --ssl --log-dir "$work/launch-logs" >"$work/launch.out" 2>"$work/launch.err" </dev/null
  status=$?
  [ "$status" = 1 ] || fail "launch.sh --ssl: exit $status, expected 1"
  grep -q "(pid $first).*; with the SSL bridge also --ssl-port-offset N$" "$work/launch.err" ||
    fail "launch.sh --ssl: no --ssl-port-offset in its line: $(cat "$work/launch.err")"
  [ -e "$work/launch-logs" ] && fail "launch.sh --ssl made its log folder (started?)"
fi

# 3. Killed, the first leaves no claim behind.
kill -KILL "$first"
wait "$first" 2>/dev/null
physics after_crash
after_crash=$!
sleep 1.5
still_running "$after_crash" "a physics after the first was killed"
kill -TERM "$after_crash"
wait "$after_crash" || fail "the physics after the crash did not stop cleanly"

# 5. Two launches at one instant: one runs, the other exits 1 naming the
#    winner's physics and starts no emulator (it may pass the check before the
#    winner's physics claims the bus: then its own physics refuses).
for run in a b; do
  "$source_dir/tools/launch.sh" --log-dir "$work/race-$run" >"$work/race-$run.out" 2>"$work/race-$run.err" </dev/null &
  started+=($!)
  eval "race_$run=\$!"
done
sleep 4
losers=0
for run in a b; do
  pid_var=race_$run
  if kill -0 "${!pid_var}" 2>/dev/null; then continue; fi
  losers=$((losers + 1))
  wait "${!pid_var}"
  status=$?
  echo "launch.sh $run lost the race -> exit $status: $(cat "$work/race-$run.err")"
  [ "$status" = 1 ] || fail "the race's loser: exit $status, expected 1"
  [ "$(wc -l <"$work/race-$run.err")" = 1 ] || fail "the race's loser: not one line on stderr"
  grep -q "^launch: ubersim_physics: another ubersim_physics (pid [0-9]*)" "$work/race-$run.err" ||
    fail "the race's loser does not name the winner"
  grep -qE "^  (vision|radio) " "$work/race-$run.out" && fail "the race's loser started emulators: $(cat "$work/race-$run.out")"
done
[ "$losers" = 1 ] || fail "two launches at one instant: $losers exited, expected 1"
for run in a b; do
  pid_var=race_$run
  kill -0 "${!pid_var}" 2>/dev/null || continue
  grep -q "exited with status" "$work/race-$run.err" && fail "the race's winner lost a process: $(cat "$work/race-$run.err")"
  kill -TERM "${!pid_var}"
  wait "${!pid_var}"
  status=$?
  [ "$status" = 143 ] || fail "the race's winner: exit $status after SIGTERM, expected 143"
done

finish "$work"
