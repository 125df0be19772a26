#!/usr/bin/env bash
# tools/launch.sh checks its command line before it starts anything: a bad
# number, an unknown scenario, profile or field, an option without its value
# each exit 2 with one readable line, start no process and make no log
# folder (once with TMPDIR unset). A program that still fails at start (here
# physics, on a misspelt key in its config) has its error line shown by
# launch.sh, not only its log's path.
# Usage: test_launch_errors.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build)
set -uo pipefail
source_dir=$1
launch=$source_dir/tools/launch.sh
work=$(mktemp -d "${TMPDIR:-/tmp}/launch-errors-XXXXXX")
# In every command line, so that a process it started would be found by it.
marker="launcherrors$$"
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"


# expect_usage_error WHAT ENV... -- ARGS...: exit 2, one line on stderr holding WHAT,
# nothing on stdout, no log folder, no process.
expect_usage_error() {
  local what=$1 environment=()
  shift
  while [ "$1" != -- ]; do environment+=("$1"); shift; done
  shift
  rm -rf "$work/logs"
  env "${environment[@]}" timeout 20 "$launch" --channel-prefix "$marker" "$@" \
    >"$work/stdout" 2>"$work/stderr" </dev/null
  local status=$?
  echo "launch.sh $* -> exit $status: $(head -c 300 "$work/stderr")"
  [ "$status" = 2 ] || fail "$*: exit $status, expected 2"
  [ "$(wc -l <"$work/stderr")" = 1 ] || fail "$*: not one line on stderr: $(cat "$work/stderr")"
  grep -qF -- "$what" "$work/stderr" || fail "$*: no '$what' on stderr"
  grep -q "unbound variable" "$work/stderr" && fail "$*: bash's unbound variable"
  [ -s "$work/stdout" ] && fail "$*: printed on stdout (started?): $(head -c 300 "$work/stdout")"
  [ -e "$work/logs" ] && fail "$*: made the log folder"
  [ -z "$(processes_of_this_test)" ] || fail "$*: left processes $(processes_of_this_test)"
}

expect_usage_error "--speed: -5 is not at least 0" -- --speed -5 --log-dir "$work/logs"
expect_usage_error "--scenario: no scenario 'nosuch'" -- --scenario nosuch --log-dir "$work/logs"
expect_usage_error "--profile: no vision profile 'nosuch'" -- --profile nosuch --log-dir "$work/logs"
expect_usage_error "--field: no field 'nosuch'" -- --field nosuch --log-dir "$work/logs"
expect_usage_error "--team: colour 'green' is not yellow, blue or both" -- --team green 'true' --log-dir "$work/logs"
expect_usage_error "--team yellow: yellow has a program already" -- --team both 'true' --team yellow 'true' --log-dir "$work/logs"
expect_usage_error "--team yellow: the yellow demo team plays that colour" -- --demo yellow --team yellow 'true' --log-dir "$work/logs"
expect_usage_error "--team needs a colour and a command" -- --team blue
expect_usage_error "--team-deterministic: only with --sync and --team" -- --team-deterministic --team blue 'true' --log-dir "$work/logs"
expect_usage_error "--team both: an LCM program plays one colour" -- --team both 'lcm:true' --log-dir "$work/logs"
expect_usage_error "--team-charge-us: only with --sync and --team" -- --team-charge-us 50 --team blue 'grsim:true' --log-dir "$work/logs"
expect_usage_error "--team-yield-after-ms: 'x' is not a number" -- --sync --team-yield-after-ms x --team blue 'grsim:true' --log-dir "$work/logs"
expect_usage_error "--seed: 'x' is not a whole number" -- --seed x --log-dir "$work/logs"
expect_usage_error "--sync-clients: 3 is not in [0, 2]" -- --sync-clients 3 --log-dir "$work/logs"
expect_usage_error "--sync-timeout: 0 is not greater than 0" -- --sync --sync-timeout 0 --log-dir "$work/logs"
expect_usage_error "--sync-timeout: only with --sync" -- --sync-timeout 5 --log-dir "$work/logs"
expect_usage_error "--sync-timeout needs a value" -- --sync --sync-timeout
expect_usage_error "--viewer-port: 0 is not in [1, 65535]" -- --viewer-port 0 --log-dir "$work/logs"
expect_usage_error "--game-length: 0 is not greater than 0" -- --game-length 0 --log-dir "$work/logs"
expect_usage_error "--repeat-games: only with --referee" -- --repeat-games --log-dir "$work/logs"
expect_usage_error "--repeat-games: not with --sync" -- --referee --repeat-games --sync --log-dir "$work/logs"
expect_usage_error "--duration: 'soon' is not a number" -- --duration soon --log-dir "$work/logs"
expect_usage_error "--scenario needs a value" -- --log-dir "$work/logs" --scenario
expect_usage_error "--scenario needs a value" -- --scenario --speed 2 --log-dir "$work/logs"
# The SSL bridge's options: values, only with the bridge, not contradicting each other.
expect_usage_error "--vision-port: 0 is not in [1, 65535]" -- --ssl --vision-port 0 --log-dir "$work/logs"
expect_usage_error "--vision-ttl: 256 is not in [0, 255]" -- --ssl --vision-ttl 256 --log-dir "$work/logs"
expect_usage_error "--vision-interface: '10.0.0' is not an IPv4 address" -- --ssl --vision-interface 10.0.0 --log-dir "$work/logs"
expect_usage_error "--vision-interface: '10.0.0.256' is not an IPv4 address" -- --ssl-bridge --vision-interface 10.0.0.256 --log-dir "$work/logs"
expect_usage_error "--ssl-port-offset: 40000 is not in [0, 30000]" -- --ssl --ssl-port-offset 40000 --log-dir "$work/logs"
expect_usage_error "--vision-port: only with --ssl or --ssl-bridge" -- --vision-port 10006 --log-dir "$work/logs"
expect_usage_error "--lan: only with --ssl or --ssl-bridge" -- --lan --log-dir "$work/logs"
expect_usage_error "--ssl-port-offset: only with --ssl or --ssl-bridge" -- --ssl-port-offset 5 --log-dir "$work/logs"
expect_usage_error "--lan: not with --ssl-local-only" -- --ssl --lan --ssl-local-only --log-dir "$work/logs"
expect_usage_error "--vision-ttl: not with --ssl-local-only" -- --ssl --ssl-local-only --vision-ttl 1 --log-dir "$work/logs"
expect_usage_error "--vision-port needs a value" -- --ssl --log-dir "$work/logs" --vision-port
# No TMPDIR and no --log-dir: the default log folder would go to /tmp.
before=$(ls -d /tmp/ubersim-* 2>/dev/null)
expect_usage_error "--speed: -5 is not at least 0" -u TMPDIR -- --speed -5
after=$(ls -d /tmp/ubersim-* 2>/dev/null)
[ "$before" = "$after" ] || fail "TMPDIR unset: a new folder in /tmp: $(comm -13 <(echo "$before") <(echo "$after"))"

# Physics fails at start on a misspelt key; launch.sh shows why.
cp -rL "$source_dir/config" "$work/config"
sed -i 's/^GRAVITY/GRAVTY/' "$work/config/physics/default.cfg"
UBERSIM_CONFIG_DIR=$work/config timeout 60 "$launch" --channel-prefix "$marker" \
  --log-dir "$work/failed" >"$work/stdout" 2>"$work/stderr" </dev/null
status=$?
echo "launch.sh with GRAVTY -> exit $status:"
cat "$work/stderr"
[ "$status" = 1 ] || fail "GRAVTY: exit $status, expected 1"
grep -q "launch: physics exited with status 2" "$work/stderr" || fail "GRAVTY: no exit status of physics"
grep -q "launch: physics: .*default.cfg:[0-9]*: unknown key 'GRAVTY': did you mean 'GRAVITY'?" \
  "$work/stderr" || fail "GRAVTY: physics' error line not on the terminal"
sleep 0.5
[ -z "$(processes_of_this_test)" ] || fail "GRAVTY: left processes $(processes_of_this_test)"

# --help works in any environment, also with no TMPDIR (most users' shells).
env -u TMPDIR "$launch" --help >"$work/stdout" 2>"$work/stderr" </dev/null
status=$?
echo "launch.sh --help without TMPDIR -> exit $status"
[ "$status" = 0 ] || fail "--help without TMPDIR: exit $status: $(head -c 300 "$work/stderr")"
grep -q -- "--log-dir DIR" "$work/stdout" || fail "--help without TMPDIR printed no usage"

finish "$work"
