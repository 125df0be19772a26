#!/usr/bin/env bash
# Without --sync, tools/launch.sh runs a --team command next to the set, in
# real time. When the set stops (the game's duration is over, or Ctrl-C),
# every process that command started stops with it: also the ones it forked
# and did not wait for, which a signal to its first process alone misses.
# Usage: test_launch_team_stop.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build)
set -uo pipefail
source_dir=$1
launch=$source_dir/tools/launch.sh
work=$(mktemp -d "${TMPDIR:-/tmp}/launch-team-stop-XXXXXX")
marker="launchteamstop$$"
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"
# The team: two processes in the background (named after the marker, so that
# pgrep finds them), and a first process that waits for them.
team="bash -c 'exec -a ${marker}-first-child sleep 300' & bash -c 'exec -a ${marker}-second-child sleep 300' & wait"

# children_started: true once both of the team's children run (at most 20 s).
# Anchored at the start of the command line: launch.sh, timeout and the team's
# shell hold the marker too, in the team command they were given.
children_started() {
  for _ in $(seq 200); do
    [ "$(pgrep -fc -- "^${marker}-(first|second)-child")" = 2 ] && return 0
    sleep 0.1
  done
  return 1
}

# The game's duration ends the set.
timeout 60 "$launch" --channel-prefix "$marker" --duration 3 --log-dir "$work/duration" \
  --team yellow "$team" >"$work/stdout" 2>"$work/stderr" </dev/null
status=$?
echo "launch.sh --duration 3 --team yellow (two children) -> exit $status"
cat "$work/stderr"
[ "$status" = 0 ] || fail "duration: exit $status, expected 0"
grep -q "did not stop within 2 s" "$work/stderr" && fail "duration: the team needed SIGKILL"
left=$(processes_of_this_test)
[ -z "$left" ] || fail "duration: left processes: $(ps -o pid=,args= -p "${left//$'\n'/,}")"

# Ctrl-C ends the set.
timeout 60 "$launch" --channel-prefix "$marker" --log-dir "$work/interrupted" \
  --team blue "$team" >"$work/stdout" 2>"$work/stderr" </dev/null &
launch_pid=$!
children_started || fail "Ctrl-C: the team's children did not start within 20 s"
kill -INT "$launch_pid"
wait "$launch_pid"
status=$?
echo "launch.sh --team blue (two children), SIGINT -> exit $status"
[ "$status" = 130 ] || fail "Ctrl-C: exit $status, expected 130: $(cat "$work/stderr")"
left=$(processes_of_this_test)
[ -z "$left" ] || fail "Ctrl-C: left processes: $(ps -o pid=,args= -p "${left//$'\n'/,}")"

pkill -KILL -f -- "$marker"
finish "$work"
