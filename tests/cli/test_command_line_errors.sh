#!/usr/bin/env bash
# Every program answers a bad command line the same way: exit 2 and one short
# line on stderr that names the option and, for a number, its range in plain
# numbers (never CLI11's 300-digit "largest double"); --help still exits 0.
# Then a config error: every program that reads a config exits 2 on one,
# naming the config; and a misspelt key in a real config folder:
# ubersim_physics names the line of the typo and the key it meant.
# Usage: test_command_line_errors.sh SOURCE_DIR NAME=PATH...  (the programs built)
set -uo pipefail
source_dir=$1
shift
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"

# A bad command line for each program, and what its error line must hold.
declare -A bad_args expected
bad_args[ubersim_physics]="--speed -5"
expected[ubersim_physics]="--speed: -5 is not at least 0"
bad_args[ubersim_vision]="--seed ten"
expected[ubersim_vision]="--seed: 'ten' is not a whole number"
bad_args[ubersim_radio]="--sync-clients 3"
expected[ubersim_radio]="--sync-clients: 3 is not in [0, 2]"
bad_args[ubersim_referee]="--timeout 0 ping"
expected[ubersim_referee]="--timeout: 0 is not greater than 0"
bad_args[ubersim_ssl_bridge]="--vision-port 70000"
expected[ubersim_ssl_bridge]="--vision-port: 70000 is not in [1, 65535]"
bad_args[ubersim_viewer]="--display-rate 0.5"
expected[ubersim_viewer]="--display-rate: 0.5 is not in [1, 240]"
bad_args[ubersim_demo_team]="--rate -60"
expected[ubersim_demo_team]="--rate: -60 is not greater than 0"
bad_args[ubersim_logger]="--no-such-option game.lcmlog"
expected[ubersim_logger]="--no-such-option"
bad_args[ubersim_dds_bridge]="--domain 300"
expected[ubersim_dds_bridge]="--domain: 300 is not in [0, 232]"
bad_args[ubersim_config_check]="nosuchkind x.cfg"
expected[ubersim_config_check]="nosuchkind"
bad_args[ubersim_log_compare]="--channels"
expected[ubersim_log_compare]="--channels"
bad_args[ubersim_gc_link]="--tick-period 5"
expected[ubersim_gc_link]="--tick-period: 5 is not in [0.001, 1]"

# A config that does not exist (or does not load) for each program that reads
# one; the viewer, the demo team, the logger and log_compare read none.
declare -A config_args
config_args[ubersim_physics]="--scenario no_such_scenario --speed 0 --duration 0.01"
config_args[ubersim_vision]="--profile no_such_profile"
config_args[ubersim_radio]="--profile no_such_profile"
config_args[ubersim_referee]="auto --game no_such_game"
config_args[ubersim_gc_link]="--gc-address 127.0.0.1:1 --game no_such_game --timeout 1"
config_args[ubersim_ssl_bridge]="--ball no_such_ball"
config_args[ubersim_dds_bridge]="--config no_such_config"
config_args[ubersim_config_check]="robots $source_dir/tests/data/bad_robot.cfg"
declare -A config_named
config_named[ubersim_config_check]="bad_robot.cfg:5"

out=$(mktemp -d "${TMPDIR:-/tmp}/cli-errors-XXXXXX")
for program_arg in "$@"; do
  name=${program_arg%%=*}
  program=${program_arg#*=}
  if [ -z "${bad_args[$name]+set}" ]; then
    fail "$name: no bad command line to try (add one to this test)"
    continue
  fi
  # shellcheck disable=SC2086  # the arguments are words on purpose
  timeout 20 "$program" ${bad_args[$name]} >"$out/stdout" 2>"$out/stderr" </dev/null
  status=$?
  lines=$(wc -l <"$out/stderr")
  longest=$(awk '{ if (length > n) n = length } END { print n + 0 }' "$out/stderr")
  echo "$name ${bad_args[$name]} -> exit $status: $(head -c 300 "$out/stderr")"
  [ "$status" = 2 ] || fail "$name ${bad_args[$name]}: exit $status, expected 2"
  [ "$lines" = 1 ] || fail "$name: $lines lines on stderr, expected 1"
  [ "$longest" -le 200 ] || fail "$name: a line of $longest characters"
  grep -qF -- "${expected[$name]}" "$out/stderr" || fail "$name: no '${expected[$name]}' on stderr"
  grep -qE '[0-9]{20}' "$out/stderr" && fail "$name: a number of 20 digits or more"
  [ -s "$out/stdout" ] && fail "$name: printed on stdout: $(head -c 200 "$out/stdout")"

  timeout 20 "$program" --help >"$out/stdout" 2>"$out/stderr" </dev/null
  status=$?
  [ "$status" = 0 ] || fail "$name --help: exit $status, expected 0"
  grep -q -i "usage" "$out/stdout" || fail "$name --help: no usage on stdout"
done

# A config error: exit 2, and the error names the config.
for program_arg in "$@"; do
  name=${program_arg%%=*}
  [ -n "${config_args[$name]+set}" ] || continue
  # shellcheck disable=SC2086  # the arguments are words on purpose
  timeout 20 "${program_arg#*=}" ${config_args[$name]} >"$out/stdout" 2>"$out/stderr" </dev/null
  status=$?
  named=${config_named[$name]:-no_such_}
  echo "$name ${config_args[$name]} -> exit $status: $(head -c 300 "$out/stderr")"
  [ "$status" = 2 ] || fail "$name with a config error: exit $status, expected 2"
  grep -qF -- "$named" "$out/stderr" || fail "$name with a config error: no '$named' on stderr"
done

# A negative seed: CLI11 alone would wrap it into an unsigned seed and run.
for program_arg in "$@"; do
  name=${program_arg%%=*}
  case $name in ubersim_physics|ubersim_vision|ubersim_radio) ;; *) continue ;; esac
  timeout 20 "${program_arg#*=}" --seed -5 >"$out/stdout" 2>"$out/stderr" </dev/null
  status=$?
  echo "$name --seed -5 -> exit $status: $(head -c 300 "$out/stderr")"
  [ "$status" = 2 ] || fail "$name --seed -5: exit $status, expected 2"
  grep -qF -- "--seed: '-5' is not a whole number" "$out/stderr" || fail "$name --seed -5: no 'is not a whole number'"
done

# A misspelt key in a copy of the shipped config folder (GRAVTY for GRAVITY):
# physics reads the physics config before it touches the bus.
physics=""
for program_arg in "$@"; do [ "${program_arg%%=*}" = ubersim_physics ] && physics=${program_arg#*=}; done
if [ -n "$physics" ]; then
  cp -rL "$source_dir/config" "$out/config"
  line=$(grep -n '^GRAVITY' "$out/config/physics/default.cfg" | cut -d: -f1)
  sed -i 's/^GRAVITY/GRAVTY/' "$out/config/physics/default.cfg"
  timeout 20 "$physics" --config-dir "$out/config" --speed 0 --duration 0.01 \
    >"$out/stdout" 2>"$out/stderr" </dev/null
  status=$?
  echo "ubersim_physics with GRAVTY -> exit $status: $(head -c 400 "$out/stderr")"
  [ "$status" = 2 ] || fail "physics with GRAVTY: exit $status, expected 2"
  grep -qF "default.cfg:$line: unknown key 'GRAVTY': did you mean 'GRAVITY'?" "$out/stderr" ||
    fail "physics with GRAVTY: the error names neither the line nor GRAVITY"
fi

finish "$out"
