#!/usr/bin/env bash
# tools/launch.sh --sync --referee: a whole refereed game of the demo teams
# runs to its end, the launcher stops everything by itself and exits 0, and
# the event log ends with the finished game's result. Logs go to a temporary
# folder, removed when the test passes. Usage: test_launch_referee.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
logs=$(mktemp -d "${TMPDIR:-/tmp}/ubersim-launch-referee-XXXXXX")
timeout 120 "$source_dir/tools/launch.sh" --sync --demo both --referee --game-length 6 --quiet \
  --log-dir "$logs" > "$logs/launch.out" 2>&1
status=$?
cat "$logs/launch.out"
if [ "$status" != 0 ]; then echo "FAIL: launch.sh exited with $status (logs in $logs)"; exit 1; fi
grep -q "the game is over" "$logs/launch.out" || { echo "FAIL: no end of game (logs in $logs)"; exit 1; }
tail -1 "$logs/events.jsonl" | grep -q '"game_over": true' || { echo "FAIL: no result line (logs in $logs)"; exit 1; }
grep -q '"command": "NORMAL_START", "stage": "NORMAL_SECOND_HALF"' "$logs/events.jsonl" || {
  echo "FAIL: the second half never started (logs in $logs)"; exit 1; }
rm -rf "$logs"
echo "PASS"
