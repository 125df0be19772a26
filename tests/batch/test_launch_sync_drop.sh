#!/usr/bin/env bash
# tools/launch.sh --sync --referee with the yellow demo team stopped (SIGSTOP)
# in the middle of the game: the radio emulator drops it after 1 s of wall
# time and the game goes on. The terminal must say so as it happens (who, at
# which sim time), say when it rejoins after SIGCONT, end with a summary of
# the time yellow was without control, and the referee's final score must say
# the result is degraded. Logs go to a temporary folder, removed when the
# test passes. Usage: test_launch_sync_drop.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
logs=$(mktemp -d "${TMPDIR:-/tmp}/ubersim-launch-sync-drop-XXXXXX")
out=$logs/launch.out
yellow="" launch=""
fail() {
  echo "FAIL: $* (logs in $logs)"
  [ -z "$yellow" ] || kill -CONT "$yellow" 2>/dev/null
  if [ -n "$launch" ]; then
    kill "$launch" 2>/dev/null
    wait "$launch"
    cat "$out"
  fi
  exit 1
}
# wait_for SECONDS WHAT COMMAND...: until COMMAND succeeds.
wait_for() {
  local seconds=$1 what=$2
  shift 2
  for _ in $(seq $((seconds * 20))); do "$@" && return 0; sleep 0.05; done
  fail "no $what within $seconds s"
}

# 120 s of game: a sync game runs at ~25x, so a 30 s one could end (1.3 s of
# wall time) before this script, descheduled on a busy machine, stopped yellow.
"$source_dir/tools/launch.sh" --sync --demo both --referee --game-length 120 --quiet \
  --log-dir "$logs" > "$out" 2>&1 &
launch=$!
wait_for 30 "yellow demo team" grep -q '^  demo_yellow ' "$out"
yellow=$(awk '$1 == "demo_yellow" { print $3 }' "$out")
wait_for 30 "kick-off" grep -q '"NORMAL_START"' "$logs/events.jsonl"
kill -STOP "$yellow"
wait_for 20 "drop on the terminal" grep -q '^launch: radio: sync client dropped: team yellow' "$out"
kill -CONT "$yellow"
wait_for 20 "rejoin on the terminal" grep -q '^launch: radio: sync client rejoined: team yellow' "$out"
wait "$launch"
status=$?
launch=""
cat "$out"
[ "$status" = 0 ] || fail "launch.sh exited with $status"
grep -q "the game is over (result: .*, DEGRADED: yellow without control for [0-9.]* s of sim time (sync client 'demo_yellow' dropped 1 time))" "$out" ||
  fail "the referee's final score does not say the result is degraded"
grep -qE "^launch: radio: sync client dropped: team yellow, client 'demo_yellow', at sim time [0-9.]+ s" "$out" ||
  fail "the drop does not say who and when"
grep -qE "^launch: sync: degraded run: yellow without control for [0-9.]+ s of sim time \(1 drop of client 'demo_yellow', back by the end\)" "$out" ||
  fail "no summary line at the end"
tail -n 1 "$out" | grep -q '^launch: sync: degraded run: ' || fail "the summary is not the last line"
rm -rf "$logs"
echo "PASS"
