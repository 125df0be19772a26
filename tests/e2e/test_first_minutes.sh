#!/usr/bin/env bash
# A new user's first minutes, in a real terminal (tmux) with TMPDIR unset, as
# most machines have it (issue 27):
#   1. tools/launch.sh --help prints the help and exits 0;
#   2. tools/demo.sh prints the viewer's address before anything else of
#      launch.sh's, on the first free port from 8080 (8080 is taken here), the
#      viewer answers there, and the desktop's browser is asked to open it
#      (real xdg-open; the "browser" registered for http records its URL);
#   3. Ctrl-C stops the set with "launch: stopped (Ctrl-C)" and exit 130,
#      names no process as failed and leaves none behind; SIGTERM the same
#      with "launch: stopped (SIGTERM)" and 143.
# Usage: test_first_minutes.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build)
set -uo pipefail
source_dir=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/first-minutes-XXXXXX")
export TMUX_TMPDIR=$work
marker="firstminutes$$"
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"
command -v tmux >/dev/null || { echo "test_first_minutes: tmux is not installed (tools/install-deps.sh installs it)"; exit 1; }
terminal() { tmux -L "terminals$$" "$@"; }
# in_terminal NAME COMMAND: runs COMMAND in a terminal of its own, then prints its exit status.
in_terminal() { terminal new-session -d -s "$1" -x 220 -y 50 "$2; echo EXIT=\$?; sleep 600"; }
screen_of() { terminal capture-pane -p -J -S - -t "$1"; }
# wait_for NAME PATTERN SECONDS: until the terminal shows PATTERN (grep -E).
wait_for() {
  for _ in $(seq $(($3 * 10))); do
    screen_of "$1" | grep -qE -- "$2" && return 0
    sleep 0.1
  done
  fail "terminal $1 did not show '$2' within $3 s; it shows:"
  screen_of "$1" | tail -n 30
  return 1
}
port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
cleanup() {
  terminal kill-server 2>/dev/null
  [ -z "${holder:-}" ] || kill "$holder" 2>/dev/null
}
trap cleanup EXIT

# 1. --help with TMPDIR unset.
in_terminal help "env -u TMPDIR $source_dir/tools/launch.sh --help"
if wait_for help "EXIT=" 20; then
  screen_of help | grep -q "usage: tools/launch.sh" || fail "--help printed no usage"
  screen_of help | grep -q "EXIT=0" || fail "--help did not exit 0"
  screen_of help | grep -q "unbound variable" && fail "--help hit an unbound variable"
fi

# 2. The demo, with 8080 taken by something else and a desktop whose browser records.
if ! port_in_use 8080; then
  python3 -c 'import socket, time
s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(("127.0.0.1", 8080)); s.listen(); time.sleep(600)' &
  holder=$!
  for _ in $(seq 50); do port_in_use 8080 && break; sleep 0.1; done
fi
mkdir -p "$work/user/config" "$work/user/data/applications"
printf '#!/bin/sh\necho "$1" > "%s/opened-url"\n' "$work" >"$work/user/record-url"
chmod +x "$work/user/record-url"
printf '[Desktop Entry]\nType=Application\nName=Recording browser\nExec=%s %%u\nMimeType=x-scheme-handler/http;\n' \
  "$work/user/record-url" >"$work/user/data/applications/ubersim-test-browser.desktop"
printf '[Default Applications]\nx-scheme-handler/http=ubersim-test-browser.desktop\n' >"$work/user/config/mimeapps.list"
desktop="DISPLAY=:0 HOME=$work/user XDG_CONFIG_HOME=$work/user/config XDG_DATA_HOME=$work/user/data"
in_terminal demo "env -u TMPDIR -u WAYLAND_DISPLAY $desktop UBERSIM_BUILD_DIR=${UBERSIM_BUILD_DIR:-} \
$source_dir/tools/demo.sh --channel-prefix $marker --log-dir $work/logs"
if wait_for demo "Ctrl-C stops everything" 300; then
  launch_output=$(screen_of demo | sed -n '/^viewer: \|^ubersim: /,$p')
  echo "$launch_output" | head -n 3
  first=$(echo "$launch_output" | head -n 1)
  [[ $first =~ ^viewer:\ +http://127\.0\.0\.1:([0-9]+)/ ]] || fail "launch.sh's first line is not the viewer's address: $first"
  port=${BASH_REMATCH[1]:-0}
  [ "$port" != 8080 ] || fail "the viewer was given 8080, which was taken"
  page=$( (exec 3<>"/dev/tcp/127.0.0.1/$port" && printf 'GET / HTTP/1.0\r\nHost: x\r\n\r\n' >&3 && timeout 5 cat <&3) 2>/dev/null)
  grep -qi "<html" <<<"$page" || fail "no page from the viewer on port $port: $(head -c 200 <<<"$page")"
  for _ in $(seq 100); do [ -s "$work/opened-url" ] && break; sleep 0.1; done
  [ "$(cat "$work/opened-url" 2>/dev/null)" = "http://127.0.0.1:$port/" ] ||
    fail "the browser was not asked to open http://127.0.0.1:$port/ (it got: $(cat "$work/opened-url" 2>/dev/null))"
  sleep 1  # let the game run a moment
fi
# 3. Ctrl-C, as the user presses it.
terminal send-keys -t demo C-c
if wait_for demo "EXIT=" 20; then
  screen_of demo | grep -q "launch: stopped (Ctrl-C)" || fail "Ctrl-C: no 'launch: stopped (Ctrl-C)'"
  screen_of demo | grep -q "EXIT=130" || fail "Ctrl-C: exit status not 130: $(screen_of demo | grep EXIT=)"
  screen_of demo | grep -q "exited with status" && fail "Ctrl-C named a process as failed: $(screen_of demo | grep 'exited with status')"
fi
[ -z "$(processes_of_this_test)" ] || fail "processes left after Ctrl-C: $(processes_of_this_test)"
# SIGTERM to launch.sh itself (a service manager's stop).
in_terminal term "env -u TMPDIR UBERSIM_BUILD_DIR=${UBERSIM_BUILD_DIR:-} $source_dir/tools/launch.sh \
--demo both --channel-prefix ${marker}t --log-dir $work/logs-term"
if wait_for term "Ctrl-C stops everything" 30; then
  # launch.sh itself, not the terminal's shell whose command line holds the same words.
  launch_pid=$(pgrep -f -- "^(/usr/bin/)?bash [^ ]*tools/launch.sh --demo both --channel-prefix ${marker}t")
  kill -TERM "$launch_pid"
  if wait_for term "EXIT=" 20; then
    screen_of term | grep -q "launch: stopped (SIGTERM)" || fail "SIGTERM: no 'launch: stopped (SIGTERM)'"
    screen_of term | grep -q "EXIT=143" || fail "SIGTERM: exit status not 143: $(screen_of term | grep EXIT=)"
  fi
fi
[ -z "$(processes_of_this_test)" ] || fail "processes left after SIGTERM: $(processes_of_this_test)"

cleanup
trap - EXIT
if [ "$failures" = 0 ]; then
  echo "test_first_minutes: passed"
  rm -rf "$work"
  exit 0
fi
echo "test_first_minutes: $failures failure(s); terminals' output and logs kept in $work"
exit 1
