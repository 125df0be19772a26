#!/usr/bin/env bash
# A team program whose thread polls without blocking, under the time shim at
# the default charge (1 us a call, a pause every 1 ms), plays far slower than
# real time: tools/launch.sh says so on the terminal while the game runs, with
# the options that trade the polling for speed (docs/timeshim.md, "Team
# programs that poll"), the bridge's summary counts the pauses, and at the end
# launch.sh says how much CPU time the team program used per game second.
# Usage: test_polling_hint.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build)
set -uo pipefail
source_dir=$1
python=/usr/bin/python3
if [ ! -x "$python" ]; then
  echo "SKIP: $python not found: the polling team is a Python program"
  exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/polling-hint-XXXXXX")
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"
# Each turn of the loop computes for some microseconds besides its clock read:
# a million turns per game second are seconds of wall time on any machine.
cat >"$work/poller.py" <<'PY'
import time
while True:
    time.monotonic()
    sum(range(1000))
PY

timeout 120 "$source_dir/tools/launch.sh" --sync --duration 0.5 --log-dir "$work/logs" \
  --team both "exec $python $work/poller.py" >"$work/stdout" 2>"$work/stderr" </dev/null
status=$?
echo "launch.sh --sync --duration 0.5 --team both (a polling loop) -> exit $status"
cat "$work/stderr"
[ "$status" = 0 ] || fail "exit $status, expected 0"
hint=$(grep "^launch: timeshim hint: team both: threads that poll without blocking paused" "$work/stderr")
[ -n "$hint" ] || fail "no hint about the polling on the terminal"
[[ $hint == *"about 1 polling the whole time"* ]] || fail "the hint does not count one polling thread: $hint"
[[ $hint == *"--team-charge-us and --team-yield-after-ms"* ]] || fail "the hint names no option: $hint"
pauses=$(grep -o 'charged pauses=[0-9]*' "$work/logs/ssl_bridge.log" | tail -n 1)
echo "bridge summary: $pauses"
# 0.5 s of game at one pause per 1 ms of charge (after the thread's free calls).
[ "${pauses#*=}" -ge 400 ] 2>/dev/null || fail "the summary counts too few pauses: '$pauses'"
cpu=$(cat "$work/stdout" "$work/stderr" | grep "^launch: team CPU: both " | head -n 1)
echo "CPU line: $cpu"
# The loop computes the whole time, and the game ran slower than real time:
# more than one CPU second per game second.
if [[ $cpu =~ both\ [0-9.]+\ s\ \(([0-9]+)\.[0-9]+\ per\ game\ s\),\ the\ bridge ]]; then
  [ "${BASH_REMATCH[1]}" -ge 1 ] || fail "the team used less than 1 CPU s per game s: $cpu"
else
  fail "no CPU line for the team and the bridge on the terminal"
fi

finish "$work"
