#!/usr/bin/env bash
# Starts the ubersim process set: physics, vision emulator, radio emulator, and
# optionally demo teams and a logger. Prints what runs, where each process
# logs and which channels to listen to. On Ctrl-C (or SIGTERM), or when any
# process dies, it stops all the others (SIGTERM, then SIGKILL after 2 s) and
# leaves none behind; it exits non-zero if any process failed on its own, and
# with 130 (Ctrl-C) or 143 (SIGTERM) when stopped by a signal. A bad option
# or value is told in one line and exits 2 before anything starts.
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
bin_dir="${UBERSIM_BUILD_DIR:-$root/build}/bin"

usage() {
  cat <<USAGE
usage: tools/launch.sh [options]
  --ssl                one command for an SSL team (coming from grSim or the ER-Force simulator):
                       physics, vision and radio emulators, the SSL bridge with tracked frames,
                       grSim's protocol (UDP 20011), the simulation protocol (10300-10302), a
                       referee on 224.5.23.1:10003 (the automatic one; --referee official: the
                       game controller's) and the viewer; prints every port a team needs;
                       in real time a new game follows each (--repeat-games)
  --scenario NAME      robots, ball and field (default division_b_6v6)
  --field NAME         field2002 | division_b | division_a: that field's default scenario;
                       any other config/fields/NAME.cfg (erforce_2014 ... erforce_2023b):
                       the scenario of the nearest size, its places scaled to the field;
                       with --scenario: that scenario's line-up on this field
  --profile NAME       vision and radio emulator profile (default cmdragons02); ER-Force's realism
                       presets as none | friendly | rc2021 | realistic (= erforce_NAME)
  --speed F            1 real time (default), 0.5, 4 ..., 0 as fast as possible (never ahead
                       of what the vision emulator can take: no frame lost; docs/vision.md)
  --lockstep           physics advances only when told (referee step N)
  --sync               sync mode: as fast as the demo teams' answers allow, latency exact and
                       runs reproducible (docs/sync.md); the demo teams answer every frame
  --sync-strict        in sync mode, a client that misses the timeout fails the run
  --sync-timeout S     in sync mode, s of wall time a sync client may hold the simulation back
                       before the radio emulator drops it (default 1; with --team: 30, as the
                       time shim names a team thread that is stuck after 2 s, and a team
                       program that computes long at one sim instant must not be dropped)
  --sync-clients N     clients physics waits for at the start (default: the demo teams started;
                       with --ssl-bridge, 2: each colour no demo team plays is an SSL team's)
  --referee [builtin|official]
                       builtin (the default with no value): start ubersim's automatic referee
                       (ubersim_referee auto, docs/autoref.md): it runs the game and everything
                       stops when it is over; with --sync, reproducibly.
                       official: the official ssl-game-controller you run referees (its Referee
                       messages on 224.5.23.1:10003); implies --ssl-bridge, which forwards them to
                       REFEREE and sends no Referee of ubersim's (docs/official_stack.md).
                       official with --sync: the game controller given by --game-controller
                       referees at full speed in its CI mode, sim time its clock (ubersim_gc_link,
                       docs/official_gc.md); everything stops when the game is over
  --game-controller PATH
                       the ssl-game-controller binary for --referee official --sync
  --game-length S      the refereed game's length in s of sim time (default: config/referee)
  --yellow-name NAME, --blue-name NAME
                       the teams' names on the referee's messages (default: config/referee,
                       Yellow and Blue); an SSL AI that finds its colour by name needs its own
  --repeat-games       with the built-in referee: a new game starts 5 s after each one ends,
                       until Ctrl-C, instead of everything stopping (tools/demo.sh)
  --truth-every-step   physics publishes SIM_STATE after every step (default: only at the
                       instants its consumers ask for: vision captures and releases, radio
                       feedback, viewer frames, bridges; docs/sync.md). Use it to record every step
  --cpu N|all          the CPU physics, vision and radio share, or all to let the kernel spread
                       them; default: in real time (up to 4x) the last CPU this script may use,
                       with --sync, --lockstep or faster speeds all (docs/design.md, "One core")
  --seed N             seed for physics, both emulators and the SSL bridge's source ids
  --duration S         stop everything after S seconds of sim time
  --lcm-url URL        LCM URL for every process (default \$LCM_DEFAULT_URL or LCM's)
  --channel-prefix P   prefix every channel (to run several simulations side by side)
  --no-vision          do not start the vision emulator (a real vision server publishes VISION)
  --no-radio           do not start the radio emulator (a real radio server listens on RADIO_<TEAM>)
  --demo WHO           start the demo team for yellow | blue | both | none (default none)
  --demo-mode MODE     play | positions | figure8 (default play)
  --log FILE           record every channel into FILE (an LCM log: lcm-logplayer replays it)
  --log-dir DIR        where process logs go (default: a new folder under \$TMPDIR or /tmp)
  --viewer             start the browser viewer (ubersim_viewer) and print its address
  --viewer-port P      the viewer's port on 127.0.0.1 (default: the first free one from 8080)
  --open-viewer        --viewer, and open it in the desktop's browser (xdg-open) when there is a
                       desktop session (DISPLAY or WAYLAND_DISPLAY set); tools/demo.sh uses it
  --ssl-bridge         start the SSL protocol bridge (SSL-Vision on 224.5.23.2:10020, tracked
                       frames on 224.5.23.2:10010, simulation control on 10300, robot control on
                       10301 blue / 10302 yellow); with --sync an SSL team answers every detection
                       packet with one RobotControl
  --no-tracked         with --ssl-bridge: send no tracked frames
  --team COLOUR 'COMMAND'
                       run COMMAND (sh -c) as the yellow, blue or both teams' program, an unchanged
                       SSL team (simulation protocol on 10301/10302); implies --ssl-bridge;
                       repeatable, once per colour. With --sync the bridge starts it under the
                       time shim on simulation time, stamping its commands with their send
                       time (docs/timeshim.md); without, it runs in real time. Its output goes
                       to team_COLOUR.log in the log folder. 'lcm:COMMAND': the program speaks
                       ubersim's LCM contract instead (VISION, VISION_GEOMETRY, REFEREE in,
                       RADIO_<TEAM> out, e.g. ubersim_demo_team without --sync); with --sync it
                       gets a private LCM bus that the bridge relays, timed. 'grsim:COMMAND':
                       the program speaks grSim's protocol (SSL-Vision in, grSim_Packet to UDP
                       20011 out, e.g. NeonFC-SSL); with --sync its grSim commands are timed
                       too, and grSim commands for a colour no 'grsim:' program plays are
                       dropped
  --team-deterministic with --sync and --team: the team programs' threads run one at a time in
                       a fixed order (reruns identical also when their threads race; slower)
  --team-charge-us US, --team-yield-after-ms MS
                       with --sync and --team: sim time charged per call of a team's thread that
                       polls without blocking (default 1), and the charge after which it pauses
                       (default 1); larger: a team that polls plays faster (docs/timeshim.md)
  --lan                with --ssl / --ssl-bridge: the command ports (grSim, simulation and robot
                       control) listen on every interface, for an AI on another PC (anyone on
                       the network may command the robots: docs/threat_model.md)
  --vision-port P      with the bridge: SSL-Vision's port (default 10020; ssl-vision's own is 10006)
  --vision-interface ADDR
                       with the bridge: the address of the interface SSL-Vision leaves on
  --vision-ttl N       with the bridge: SSL-Vision's multicast TTL (0: this host only)
  --ssl-local-only     with the bridge: every SSL multicast stays on this host (TTL 0)
  --ssl-port-offset N  with the bridge: every SSL port + N (to run beside another simulator)
  --quiet              less process log output
USAGE
}

# A --team command without its protocol prefix (lcm:, grsim:).
team_program() {
  case $1 in
    lcm:*) printf '%s' "${1#lcm:}" ;;
    grsim:*) printf '%s' "${1#grsim:}" ;;
    *) printf '%s' "$1" ;;
  esac
}

# A bad command line: one line on stderr, exit 2, nothing started.
usage_error() {
  echo "launch: $*" >&2
  exit 2
}

# Options that take a value. A missing one (the end of the line, or the next
# option in its place) is an error here, not an unbound $2 below.
options_with_values=" --scenario --field --profile --speed --sync-clients --sync-timeout --game-length --cpu --seed
  --game-controller --yellow-name --blue-name --duration --lcm-url --channel-prefix --demo --demo-mode --log --log-dir --viewer-port
  --vision-port --vision-interface --vision-ttl --ssl-port-offset --team-charge-us --team-yield-after-ms "

scenario="" field="" profile=cmdragons02 speed=1 lockstep=0 sync=0 sync_strict=0 sync_clients="" sync_timeout="" truth_every_step=0 seed="" duration=""
lcm_url="${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}" prefix="" cpu=""
referee=none game_length="" tracked=1 game_controller="" yellow_name="" blue_name=""
ssl_mode=0 lan=0 vision_port="" vision_interface="" vision_ttl="" ssl_local_only=0 ssl_port_offset=0 referee_given=0
vision=1 radio=1 demo=none demo_mode=play log_file="" log_dir="" quiet=0 viewer=0 viewer_port="" open_viewer=0 ssl_bridge=0
repeat_games=0 team_yellow="" team_blue="" team_both="" team_deterministic=0 team_charge_us="" team_yield_after_ms=""
while [ $# -gt 0 ]; do
  if [[ $options_with_values == *[[:space:]]"$1"[[:space:]]* ]] && { [ $# -lt 2 ] || [[ $2 == --* ]]; }; then
    usage_error "$1 needs a value (tools/launch.sh --help lists the options)"
  fi
  case "$1" in
    --scenario) scenario=$2; shift 2 ;;
    --field) field=$2; shift 2 ;;
    --profile) profile=$2; shift 2 ;;
    --speed) speed=$2; shift 2 ;;
    --lockstep) lockstep=1; shift ;;
    --sync) sync=1; shift ;;
    --sync-strict) sync=1; sync_strict=1; shift ;;
    --team-deterministic) team_deterministic=1; shift ;;
    --team-charge-us) team_charge_us=$2; shift 2 ;;
    --team-yield-after-ms) team_yield_after_ms=$2; shift 2 ;;
    --sync-clients) sync_clients=$2; shift 2 ;;
    --sync-timeout) sync_timeout=$2; shift 2 ;;
    --referee)
      referee_given=1
      case "${2:-}" in builtin|official) referee=$2; shift 2 ;; *) referee=builtin; shift ;; esac ;;
    --no-tracked) tracked=0; shift ;;
    --game-length) game_length=$2; shift 2 ;;
    --repeat-games) repeat_games=1; shift ;;
    --game-controller) game_controller=$2; shift 2 ;;
    --yellow-name) yellow_name=$2; shift 2 ;;
    --blue-name) blue_name=$2; shift 2 ;;
    --truth-every-step) truth_every_step=1; shift ;;
    --truth-on-demand) shift ;;  # the default; accepted for older scripts
    --cpu) cpu=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    --lcm-url) lcm_url=$2; shift 2 ;;
    --channel-prefix) prefix=$2; shift 2 ;;
    --no-vision) vision=0; shift ;;
    --no-radio) radio=0; shift ;;
    --demo) demo=$2; shift 2 ;;
    --demo-mode) demo_mode=$2; shift 2 ;;
    --log) log_file=$2; shift 2 ;;
    --log-dir) log_dir=$2; shift 2 ;;
    --quiet) quiet=1; shift ;;
    --viewer) viewer=1; shift ;;
    --viewer-port) viewer_port=$2; shift 2 ;;
    --open-viewer) viewer=1; open_viewer=1; shift ;;
    --ssl-bridge) ssl_bridge=1; shift ;;
    --team)
      [ $# -ge 3 ] || usage_error "--team needs a colour and a command: --team yellow 'COMMAND'"
      [ -n "$3" ] || usage_error "--team $2: the command is empty"
      case "$2" in
        yellow) [ -z "$team_yellow$team_both" ] || usage_error "--team yellow: yellow has a program already"; team_yellow=$3 ;;
        blue) [ -z "$team_blue$team_both" ] || usage_error "--team blue: blue has a program already"; team_blue=$3 ;;
        both) [ -z "$team_yellow$team_blue$team_both" ] || usage_error "--team both: a colour has a program already"
              [[ $3 != lcm:* ]] || usage_error "--team both: an LCM program plays one colour (--team yellow 'lcm:COMMAND')"
              team_both=$3 ;;
        *) usage_error "--team: colour '$2' is not yellow, blue or both" ;;
      esac
      ssl_bridge=1; shift 3 ;;
    --ssl) ssl_mode=1; shift ;;
    --lan) lan=1; shift ;;
    --vision-port) vision_port=$2; shift 2 ;;
    --vision-interface) vision_interface=$2; shift 2 ;;
    --vision-ttl) vision_ttl=$2; shift 2 ;;
    --ssl-local-only) ssl_local_only=1; shift ;;
    --ssl-port-offset) ssl_port_offset=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) usage_error "unknown option '$1' (tools/launch.sh --help lists the options)" ;;
  esac
done

# --ssl: the one command for an SSL team: the bridge with tracked frames, a
# referee (the automatic one unless --referee says otherwise) and the viewer.
# In real time the built-in referee starts a new game after each, as grSim runs
# until it is closed; a synced game ends the run.
if [ "$ssl_mode" = 1 ]; then
  ssl_bridge=1 viewer=1
  [ "$referee_given" = 1 ] || referee=builtin
  [ "$referee" = builtin ] && [ "$sync" = 0 ] && repeat_games=1
fi

# The official game controller in CI mode (--referee official --sync): ubersim_gc_link drives it
# with sim time as its clock. In real time it reaches ubersim only through the SSL bridge.
gc_ci=0
if [ "$referee" = official ] && [ "$sync" = 1 ]; then
  gc_ci=1
  [ -n "$game_controller" ] || usage_error "--referee official with --sync needs --game-controller PATH (the game controller runs in its CI mode)"
  [ -x "$game_controller" ] && [ -f "$game_controller" ] || usage_error "--game-controller: '$game_controller' is not an executable file"
elif [ -n "$game_controller" ]; then
  usage_error "--game-controller: only with --referee official --sync (real time: run the game controller yourself, docs/official_stack.md)"
fi
[ "$referee" = official ] && [ "$gc_ci" = 0 ] && ssl_bridge=1

# Everything below that can be checked here is checked before anything starts,
# in the words the programs themselves use ("--speed: -5 is not at least 0").
# The programs read the same folder: UBERSIM_CONFIG_DIR, or the tree's config/.
config_dir=${UBERSIM_CONFIG_DIR:-$root/config}

is_number() { [[ $1 =~ ^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$ ]]; }
# check_number OPTION VALUE MIN [MAX]: a number in [MIN, MAX] (MAX omitted: at least MIN).
check_number() {
  is_number "$2" || usage_error "$1: '$2' is not a number"
  if [ $# -ge 4 ]; then
    awk -v v="$2" -v lo="$3" -v hi="$4" 'BEGIN { exit !(v + 0 >= lo && v + 0 <= hi) }' ||
      usage_error "$1: $2 is not in [$3, $4]"
  else
    awk -v v="$2" -v lo="$3" 'BEGIN { exit !(v + 0 >= lo) }' || usage_error "$1: $2 is not at least $3"
  fi
}
# check_positive OPTION VALUE: a number greater than 0.
check_positive() {
  is_number "$2" || usage_error "$1: '$2' is not a number"
  awk -v v="$2" 'BEGIN { exit !(v + 0 > 0) }' || usage_error "$1: $2 is not greater than 0"
}
# check_whole OPTION VALUE [MIN MAX]: a whole number (that fits 64 bits), in [MIN, MAX] if given.
check_whole() {
  [[ $2 =~ ^[0-9]{1,19}$ ]] || usage_error "$1: '$2' is not a whole number (0 or more, at most 19 digits)"
  if [ $# -ge 4 ]; then
    # Past 9 digits no range here holds it (and bash's 64-bit arithmetic may not); 10#: not octal.
    [ ${#2} -le 9 ] && (( 10#$2 >= $3 && 10#$2 <= $4 )) || usage_error "$1: $2 is not in [$3, $4]"
  fi
}
# check_ipv4 OPTION VALUE: a dotted IPv4 address.
check_ipv4() {
  local IFS=. part
  [[ $2 =~ ^[0-9]{1,3}(\.[0-9]{1,3}){3}$ ]] || usage_error "$1: '$2' is not an IPv4 address (a.b.c.d)"
  for part in $2; do (( 10#$part <= 255 )) || usage_error "$1: '$2' is not an IPv4 address (a.b.c.d)"; done
}
# The bridge's options: values, and only with the bridge, and not contradicting each other.
check_ssl_options() {
  [ -z "$vision_port" ] || check_whole --vision-port "$vision_port" 1 65535
  [ -z "$vision_ttl" ] || check_whole --vision-ttl "$vision_ttl" 0 255
  [ -z "$vision_interface" ] || check_ipv4 --vision-interface "$vision_interface"
  check_whole --ssl-port-offset "$ssl_port_offset" 0 30000
  local option
  if [ "$ssl_bridge" = 0 ]; then
    for option in lan:--lan vision_port:--vision-port vision_interface:--vision-interface \
      vision_ttl:--vision-ttl ssl_local_only:--ssl-local-only; do
      local name=${option%%:*}
      local value=${!name}
      [ -z "$value" ] || [ "$value" = 0 ] || usage_error "${option#*:}: only with --ssl or --ssl-bridge (the SSL bridge)"
    done
    [ "$((10#$ssl_port_offset))" = 0 ] || usage_error "--ssl-port-offset: only with --ssl or --ssl-bridge (the SSL bridge)"
  fi
  if [ "$ssl_local_only" = 1 ]; then
    [ -z "$vision_interface" ] || usage_error "--vision-interface: not with --ssl-local-only (it keeps SSL-Vision on this host)"
    [ -z "$vision_ttl" ] || usage_error "--vision-ttl: not with --ssl-local-only (it sends with TTL 0)"
    [ "$lan" = 0 ] || usage_error "--lan: not with --ssl-local-only (an AI on another PC would hear no vision)"
  fi
}
# config_path KIND NAME: the file a program reads for NAME, as it resolves it
# (common/src/config_paths.cpp): a path if NAME has a '/' or ends in .cfg,
# else <config folder>/KIND/NAME.cfg.
config_path() {
  case "$2" in */* | *.cfg) echo "$2" ;; *) echo "$config_dir/$1/$2.cfg" ;; esac
}
# The names a KIND of config offers, for the error: "a, b, c".
config_names() {
  local names=() file
  for file in "$config_dir/$1"/*.cfg; do [ -f "$file" ] && names+=("$(basename "$file" .cfg)"); done
  local IFS=,
  echo "${names[*]}" | sed 's/,/, /g'
}
# check_config OPTION KIND WHAT NAME: NAME is a config file of that kind
# (WHAT names one, for the error).
check_config() {
  [ -f "$(config_path "$2" "$4")" ] && return 0
  [ "$(config_path "$2" "$4")" = "$config_dir/$2/$4.cfg" ] || usage_error "$1: no file '$4'"
  local folder=${config_dir#"$root"/}/$2 names
  names=$(config_names "$2")
  # The names, unless they are too many for one line.
  [ -n "$names" ] && [ ${#names} -le 160 ] && names=" (there: $names)" || names=""
  usage_error "$1: no $3 '$4' in $folder$names"
}

check_number --speed "$speed" 0
[ -z "$seed" ] || check_whole --seed "$seed"
[ -z "$duration" ] || check_number --duration "$duration" 0
[ -z "$game_length" ] || check_positive --game-length "$game_length"
if [ "$repeat_games" = 1 ]; then
  [ "$referee" = builtin ] || usage_error "--repeat-games: only with --referee (the built-in referee)"
  [ "$sync" = 0 ] || usage_error "--repeat-games: not with --sync (physics holds at the end of a synced game)"
fi
[ -z "$sync_clients" ] || check_whole --sync-clients "$sync_clients" 0 2
[ -z "$sync_timeout" ] || check_positive --sync-timeout "$sync_timeout"
[ -z "$sync_timeout" ] || [ "$sync" = 1 ] || usage_error "--sync-timeout: only with --sync"
# 0 (any free port) would print an address nobody can open.
[ -z "$viewer_port" ] || check_whole --viewer-port "$viewer_port" 1 65535
case "$demo" in yellow|blue|both|none) ;; *) usage_error "--demo: '$demo' is not yellow, blue, both or none" ;; esac
case "$demo_mode" in play|positions|figure8) ;; *) usage_error "--demo-mode: '$demo_mode' is not play, positions or figure8" ;; esac
for team in yellow blue; do
  team_command=team_$team
  if [ -n "${!team_command}$team_both" ] && { [ "$demo" = "$team" ] || [ "$demo" = both ]; }; then
    usage_error "--team $team: the $team demo team plays that colour (--demo $demo)"
  fi
done
if [ "$team_deterministic" = 1 ] && { [ "$sync" = 0 ] || [ -z "$team_yellow$team_blue$team_both" ]; }; then
  usage_error "--team-deterministic: only with --sync and --team"
fi
for option in charge-us yield-after-ms; do
  value=team_${option//-/_}
  [ -n "${!value}" ] || continue
  { [ "$sync" = 1 ] && [ -n "$team_yellow$team_blue$team_both" ]; } ||
    usage_error "--team-$option: only with --sync and --team"
  check_number "--team-$option" "${!value}" 0 10000
done
[ -z "$log_file" ] || [ -d "$(dirname "$log_file")" ] ||
  usage_error "--log: no folder '$(dirname "$log_file")' to write '$log_file' into"
[ -z "$scenario" ] || check_config --scenario scenarios scenario "$scenario"
check_ssl_options
[ -z "$field" ] || check_config --field fields field "$field"
# ER-Force's realism presets by their short names: rc2021 is config/{vision,radio}/erforce_rc2021.cfg.
[ -e "$config_dir/vision/$profile.cfg" ] || [ ! -e "$config_dir/vision/erforce_$profile.cfg" ] || profile=erforce_$profile
[ "$vision" = 0 ] || check_config --profile vision "vision profile" "$profile"
[ "$radio" = 0 ] || check_config --profile radio "radio profile" "$profile"

# The SSL ports, from the bridge's defaults (ssl_bridge/include/ubersim/ssl_bridge/bridge.hpp and
# docs/ssl_bridge.md) shifted by --ssl-port-offset; --vision-port as given.
set_ssl_ports() {
  local offset=$((10#$ssl_port_offset))
  ssl_listen=127.0.0.1
  [ "$lan" = 1 ] && ssl_listen=0.0.0.0
  ssl_control_port=$((10300 + offset)) ssl_blue_port=$((10301 + offset)) ssl_yellow_port=$((10302 + offset))
  ssl_grsim_port=$((20011 + offset)) ssl_grsim_blue_status=$((30011 + offset)) ssl_grsim_yellow_status=$((30012 + offset))
  ssl_tracked_port=$((10010 + offset)) ssl_referee_port=$((10003 + offset))
  ssl_vision_port=${vision_port:-$((10020 + offset))}
}
set_ssl_ports
# Every port a team's software needs, in one block (the bridge's, from set_ssl_ports).
print_ssl_ports() {
  local host=$ssl_listen referee_note multicast_note=""
  if [ "$lan" = 1 ]; then
    host=$(hostname -I 2>/dev/null | awk '{ print $1 }')
    host=${host:-"<this PC's address>"}
  fi
  case "$referee" in
    builtin) referee_note="ubersim's automatic referee" ;;
    official) referee_note="the official game controller's"
      [ "$gc_ci" = 1 ] && referee_note="the official game controller (CI mode), sent by the bridge"
      [ "$gc_ci" = 0 ] && [ "$ssl_referee_port" != 10003 ] && referee_note+=" (set its publish address to this port)" ;;
    *) referee_note="nobody referees (--referee starts ubersim's automatic referee)" ;;
  esac
  [ "$ssl_local_only" = 1 ] && multicast_note=", this host only (TTL 0)"
  [ -n "$vision_interface" ] && multicast_note+=", sent on $vision_interface"
  [ -n "$vision_ttl" ] && multicast_note+=", TTL $vision_ttl"
  echo "ports for your team's software (SSL protocols):"
  local vision_hint="; an AI on ssl-vision's default port 10006: add --vision-port 10006"
  [ "$ssl_vision_port" != 10006 ] || vision_hint=""
  echo "  vision               224.5.23.2:$ssl_vision_port (SSL-Vision multicast$multicast_note)$vision_hint"
  if [ "$tracked" = 1 ]; then
    echo "  tracked              224.5.23.2:$ssl_tracked_port (TrackerWrapperPacket multicast)"
  else
    echo "  tracked              none (--no-tracked)"
  fi
  echo "  referee              224.5.23.1:$ssl_referee_port (Referee multicast), $referee_note"
  echo "  grSim commands       $host:$ssl_grsim_port (grSim_Packet); robot status to the sender's address on port $ssl_grsim_blue_status (blue) / $ssl_grsim_yellow_status (yellow)"
  echo "  simulation control   $host:$ssl_control_port (SSL simulation protocol)"
  echo "  robot control        $host:$ssl_blue_port (blue) / $host:$ssl_yellow_port (yellow)"
  [ "$viewer" = 1 ] && echo "  viewer               $viewer_url"
  if [ "$lan" = 1 ]; then
    echo "  the command ports listen on every interface of this PC (--lan): anyone on your network can command the robots"
  else
    echo "  the command ports listen on this host only; --lan opens them to an AI on another PC"
  fi
}

field_override=""
if [ -n "$scenario" ] && [ -n "$field" ]; then
  field_override=$field  # the scenario's line-up on that field
elif [ -z "$scenario" ]; then
  case "${field:-division_b}" in
    field2002) scenario=field2002_5v5 ;;
    division_b) scenario=division_b_6v6 ;;
    division_a) scenario=division_a_11v11 ;;
    *)
      # Another field: the line-up of the nearest size, scaled onto it by physics.
      field_file=$(config_path fields "$field")
      length=$(awk -F'[=#]' '/^[ \t]*FIELD_LENGTH[ \t]*=/ { gsub(/[ \t]/, "", $2); print $2 }' "$field_file" 2>/dev/null)
      is_number "$length" || usage_error "--field: $field_file has no FIELD_LENGTH = <m>"
      scenario=$(awk -v l="$length" 'BEGIN { print (l >= 10.5 ? "division_a_11v11" : l >= 4.5 ? "division_b_6v6" : "field2002_5v5") }')
      field_override=$field ;;
  esac
fi
for program in ubersim_physics ubersim_vision ubersim_radio ubersim_demo_team ubersim_logger; do
  [ -x "$bin_dir/$program" ] || { echo "launch: $bin_dir/$program not found: run tools/build.sh" >&2; exit 2; }
done
[ "$gc_ci" = 0 ] || [ -x "$bin_dir/ubersim_gc_link" ] || { echo "launch: $bin_dir/ubersim_gc_link not found (is protobuf installed?): run tools/build.sh" >&2; exit 2; }
[ "$ssl_bridge" = 0 ] || [ -x "$bin_dir/ubersim_ssl_bridge" ] || { echo "launch: $bin_dir/ubersim_ssl_bridge not found (is protobuf installed?): run tools/build.sh" >&2; exit 2; }
[ "$viewer" = 0 ] || [ -x "$bin_dir/ubersim_viewer" ] || { echo "launch: $bin_dir/ubersim_viewer not found: run tools/build.sh" >&2; exit 2; }

# In real time the set uses a few percent of a core, and every message
# between processes on different cores wakes the other core (an interrupt, in
# a VM two exits): on one core they cost a quarter less. Spread when they must
# run in parallel (sync, lockstep, beyond 4x real time).
if [ -z "$cpu" ]; then
  cpu=all
  if [ "$sync" = 0 ] && [ "$lockstep" = 0 ] && awk -v s="$speed" 'BEGIN { exit !(s > 0 && s <= 4) }'; then
    allowed=$(taskset -cp $$ 2>/dev/null) && allowed=${allowed##*: } && cpu=${allowed##*[,-]}
  fi
fi
placement=()
if [ "$cpu" != all ]; then
  [[ "$cpu" =~ ^[0-9]+$ ]] && taskset -c "$cpu" true 2>/dev/null ||
    usage_error "--cpu: '$cpu' is not a CPU this script may use, nor all"
  placement=(taskset -c "$cpu")
fi

# A second simulator on this bus or on these ports stops here, before anything
# starts: physics itself tells whether another physics holds the bus (its
# claim, docs/physics.md "One physics per bus"), and the bridge's UDP ports
# must be free (docs/failures.md).
check_no_other_simulator() {
  local line
  if ! line=$("$bin_dir/ubersim_physics" --check-bus --lcm-url "$lcm_url" ${prefix:+--channel-prefix "$prefix"} 2>&1 >/dev/null); then
    line=${line##*$'\n'}
    # Beside another run with the bridge, its SSL ports must differ too.
    [ "$ssl_bridge" = 0 ] || line+="; with the SSL bridge also --ssl-port-offset N"
    echo "launch: $line" >&2
    exit 1
  fi
  [ "$ssl_bridge" = 0 ] && return 0
  local port what holder
  for port in "$ssl_control_port:simulation control" "$ssl_blue_port:blue robot control" \
    "$ssl_yellow_port:yellow robot control" "$ssl_grsim_port:grSim commands"; do
    what=${port#*:} port=${port%%:*}
    holder=$(udp_port_holder "$ssl_listen" "$port")
    [ -z "$holder" ] && continue
    echo "launch: UDP $ssl_listen:$port ($what) is taken by $holder: another simulator runs" \
      "(grSim, the ER-Force simulator, ubersim's SSL bridge?); stop it, or run beside it with" \
      "--ssl-port-offset N (and another --lcm-url port or --channel-prefix)" >&2
    exit 1
  done
}
# udp_port_holder ADDRESS PORT: who holds UDP PORT where a bind on ADDRESS would
# meet it ("" if nobody, or if ss is not installed: the bridge then says it).
udp_port_holder() {
  command -v ss >/dev/null 2>&1 || return 0
  ss -Hulnp 2>/dev/null | awk -v want="$1" -v port="$2" '
    {
      n = split($4, parts, ":")
      if (parts[n] != port) next
      address = substr($4, 1, length($4) - length(port) - 1)
      if (want != "0.0.0.0" && address != want && address != "0.0.0.0" && address != "*" && address != "[::]") next
      holder = "- another program"
      if (match($0, /users:\(\("[^"]*",pid=[0-9]+/)) {
        split(substr($0, RSTART + 9, RLENGTH - 9), who, "\",pid=")
        holder = who[2] " " who[1]
      }
      print holder
      exit
    }' | {
    # ss gives the name the kernel keeps (15 characters); the program's own is in its command line.
    local pid name program
    read -r pid name || return 0
    [ "$pid" = - ] && { echo "$name"; return 0; }
    program=$(tr '\0' '\n' <"/proc/$pid/cmdline" 2>/dev/null | head -n 1)
    [ -z "$program" ] || name=${program##*/}
    echo "$name (pid $pid)"
  }
}
check_no_other_simulator

# The viewer's port: the one asked for, or the first free one from 8080 (a
# second demo, or anything else on 8080, must not stop the demo from starting).
port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
if [ "$viewer" = 1 ] && [ -z "$viewer_port" ]; then
  viewer_port=8080
  while port_in_use "$viewer_port" && [ "$viewer_port" -lt 8180 ]; do viewer_port=$((viewer_port + 1)); done
fi
viewer_url="http://127.0.0.1:${viewer_port}/"
# The address comes first: it is what a new user opens.
[ "$viewer" = 1 ] && echo "viewer:   $viewer_url   (open it in a browser)"

# Only now, with every check passed, the log folder.
[ -n "$log_dir" ] || log_dir=$(mktemp -d "${TMPDIR:-/tmp}/ubersim-XXXXXX")
mkdir -p "$log_dir"

common=(--lcm-url "$lcm_url")
[ -n "$prefix" ] && common+=(--channel-prefix "$prefix")
[ "$quiet" = 1 ] && common+=(-q)
seed_args=()
[ -n "$seed" ] && seed_args=(--seed "$seed")

# Why a program failed, from its log, on the terminal: its error lines
# (spdlog's [error], a command-line error "ubersim_x: ..."), else -- unless a
# signal ended it -- its last lines. The log itself holds the rest.
why_failed() {  # why_failed NAME STATUS
  local log="$log_dir/$1.log" lines line
  [ -s "$log" ] || return 0
  lines=$(grep -E '\[(error|critical)\]|^(ubersim_[a-z_]+|referee|demo_team): ' "$log" | tail -n 2)
  [ -n "$lines" ] || [ "$2" -ge 128 ] || lines=$(tail -n 2 "$log")
  while IFS= read -r line; do
    [ -z "$line" ] || echo "launch: $1: ${line:0:300}" >&2
  done <<<"$lines"
}

names=() pids=() groups=()
start() {  # start NAME COMMAND...
  local name=$1
  shift
  "$@" >"$log_dir/$name.log" 2>&1 &
  names+=("$name")
  pids+=($!)
  groups+=(0)
  printf '  %-14s pid %-7s log %s\n' "$name" "$!" "$log_dir/$name.log"
}
# start_group NAME COMMAND...: as start, in a process group of its own (setsid
# runs it in place: a background job is no group leader), so that the stop
# reaches every process the command started, not only its first one.
start_group() {
  start "$@"
  groups[-1]=1
}
# signal_entry SIGNAL INDEX: the process of pids[INDEX], or its whole group.
signal_entry() {
  if [ "${groups[$2]}" = 1 ]; then
    kill "-$1" -- "-${pids[$2]}" 2>/dev/null
  else
    kill "-$1" "${pids[$2]}" 2>/dev/null
  fi
}

sync_watch="" sync_filter=""  # the sync mode's log watch (below), once started
failed=0
# Sends SIGTERM to the given indices of pids[], waits up to 2 s, kills what is left.
stop_indices() {
  local i
  for i in "$@"; do signal_entry TERM "$i"; done
  for _ in $(seq 20); do
    local alive=0
    for i in "$@"; do signal_entry 0 "$i" && alive=1; done
    [ "$alive" = 0 ] && break
    sleep 0.1
  done
  for i in "$@"; do
    if signal_entry 0 "$i"; then
      echo "launch: ${names[$i]} did not stop within 2 s: killing it" >&2
      signal_entry KILL "$i"
      failed=1
    fi
  done
}
stop_all() {
  # The logger stops last, once every producer has exited, so that the log
  # holds every message anyone could have received during the run.
  local i producers=() loggers=()
  for i in "${!pids[@]}"; do
    if [ "${names[$i]}" = logger ]; then loggers+=("$i"); else producers+=("$i"); fi
  done
  [ "${#producers[@]}" = 0 ] || stop_indices "${producers[@]}"
  if [ "${#loggers[@]}" != 0 ]; then
    sleep 0.2  # let the logger drain what is still in its socket buffer
    stop_indices "${loggers[@]}"
  fi
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}" 2>/dev/null
    local status=$?
    # 0, or killed by the signal we sent (128+15) / Ctrl-C (128+2): a clean stop.
    # 127 and -1: bash has no status left for it. That happens when Ctrl-C
    # reached the process from the terminal and it exited while the trap was
    # starting; a process that failed on its own was reported by the main loop.
    case $status in
      0|130|143|127|-1) ;;
      *) echo "launch: ${names[$i]} exited with status $status" >&2; why_failed "${names[$i]}" "$status"; failed=1 ;;
    esac
  done
  # What the run lost, said once every process is stopped; the sync verdict last.
  report_losses
  report_team_cpu
  report_sync_clients
}

# Team programs under the time shim: the CPU time they and the bridge used
# per game second (their own computing bounds the game's speed).
report_team_cpu() {
  local line
  line=$(grep -o "team CPU: .*" "$log_dir/ssl_bridge.log" 2>/dev/null | tail -n 1)
  [ -z "$line" ] || echo "launch: $line"
}

# The end of a sync run: the radio emulator's verdict on its clients, the
# last line of its log that says one (docs/sync.md, "A dropped client").
report_sync_clients() {
  [ -n "$sync_watch" ] || return 0
  kill "$sync_watch" 2>/dev/null
  wait "$sync_watch" 2>/dev/null
  exec {sync_fd}>&-
  wait "$sync_filter" 2>/dev/null
  sync_watch=""
  local log="$log_dir/radio.log" summary drops
  summary=$(grep -o 'sync: degraded run: .*' "$log" | tail -n 1)
  drops=$(grep -c 'sync client dropped: ' "$log")
  if [ -n "$summary" ]; then
    echo "launch: $summary" >&2
  elif [ "$drops" != 0 ]; then
    echo "launch: sync: degraded run: $drops sync client drop(s), no summary from the radio emulator (see $log)" >&2
  else
    echo "launch: sync: no client was dropped"
  fi
}

# A loss is said where the user looks: frames the vision emulator lost
# (from its exit summary) are named on the terminal.
report_losses() {
  local lost line
  # Commands beyond a robot type's limits were applied at the limit: say how many.
  line=$(grep -o "commands: .*" "$log_dir/physics.log" 2>/dev/null | tail -n 1)
  if [ -n "$line" ] && [[ $line != *" 0 of them at a robot type's limit"* ]]; then
    echo "launch: physics $line (see $log_dir/physics.log)" >&2
  fi
  # grSim commands that a newer one for the same robot replaced before they went out.
  line=$(grep -o "grSim summary:.*" "$log_dir/ssl_bridge.log" 2>/dev/null | tail -n 1)
  if [[ $line =~ superseded\ yellow=([0-9]+).*superseded\ blue=([0-9]+) ]] &&
    [ "${BASH_REMATCH[1]}${BASH_REMATCH[2]}" != 00 ]; then
    echo "launch: grSim commands superseded by newer ones before they went out: yellow ${BASH_REMATCH[1]}, blue ${BASH_REMATCH[2]} (see $log_dir/ssl_bridge.log)" >&2
  fi
  lost=$(grep -o 'summary: frames lost [0-9]*' "$log_dir/vision.log" 2>/dev/null | tail -n 1)
  lost=${lost##* }
  if [ -n "$lost" ] && [ "$lost" != 0 ]; then
    echo "launch: vision lost $lost frames: no ground truth reached it for their capture instants (see $log_dir/vision.log)" >&2
  fi
}

# on_signal NAME STATUS: the user stopped the set. Exit STATUS (128 + the
# signal, as a shell does) unless a process had failed on its own. Installed
# before the first process starts: a Ctrl-C during the start stops what has
# started so far (before, it ended this script and left the rest running).
on_signal() {
  trap '' INT TERM
  stop_all
  echo "launch: stopped ($1)"
  [ "$failed" = 0 ] || exit 1
  exit "$2"
}
trap 'on_signal Ctrl-C 130' INT
trap 'on_signal SIGTERM 143' TERM

mode=$speed
[ "$lockstep" = 1 ] && mode=lockstep
[ "$sync" = 1 ] && mode=sync
echo "ubersim: scenario $scenario${field_override:+ on field $field_override}, profile $profile, speed $mode, LCM $lcm_url, CPU ${cpu}"
if [ -n "$log_file" ]; then
  # ubersim_logger, not lcm-logger: lcm-logger 1.3.1 queues only 30 messages
  # per subscription and loses SIM_STATE when physics runs ahead in bursts.
  # Its log is an ordinary LCM log (lcm-logplayer replays it).
  start logger "$bin_dir/ubersim_logger" --lcm-url "$lcm_url" --channels "${prefix}.*" "$log_file"
  # The logger must be listening before anything publishes: it creates the
  # file just before it subscribes, so wait for the file (at most 2 s).
  for _ in $(seq 20); do [ -e "$log_file" ] && break; sleep 0.1; done
  sleep 0.1
fi
physics_args=(--scenario "$scenario" --speed "$speed")
[ -n "$field_override" ] && physics_args+=(--field "$field_override")
[ "$lockstep" = 1 ] && physics_args+=(--lockstep)
[ "$truth_every_step" = 1 ] && physics_args+=(--truth-every-step)
# As fast as possible physics waits for the vision emulator to keep up; from
# the first state on, so that no frame of the run's start is lost (docs/vision.md).
if [ "$vision" = 1 ] && [ "$sync" = 0 ] && [ "$lockstep" = 0 ] && awk -v s="$speed" 'BEGIN { exit !(s == 0) }'; then
  physics_args+=(--wait-for-vision)
fi
radio_args=() demo_args=() bridge_args=()
if [ "$sync" = 1 ]; then
  # Physics holds at sim time 0 until every demo team has registered, so
  # that two runs start alike; a client of your own counts too (docs/sync.md).
  # With the SSL bridge, each colour no demo team plays is an SSL team's:
  # the bridge registers it when the team first speaks on its port.
  clients=0
  case "$demo" in yellow|blue) clients=1 ;; both) clients=2 ;; esac
  [ "$ssl_bridge" = 1 ] && clients=2
  # Team programs (--team) run under the time shim in the bridge's team group.
  # 'lcm:COMMAND': an LCM team, on a private bus the bridge relays; 'grsim:COMMAND':
  # a team that speaks grSim's protocol (docs/timeshim.md).
  for team in yellow blue both; do
    team_command=team_$team
    [ -n "${!team_command}" ] || continue
    bridge_args+=(--team-command "$team" "$(team_program "${!team_command}")")
    case ${!team_command} in
      lcm:*) bridge_args+=(--team-protocol "$team" lcm) ;;
      grsim:*) bridge_args+=(--team-protocol "$team" grsim) ;;
    esac
  done
  [ "$team_deterministic" = 0 ] || bridge_args+=(--team-deterministic)
  [ -z "$team_charge_us" ] || bridge_args+=(--team-charge-us "$team_charge_us")
  [ -z "$team_yield_after_ms" ] || bridge_args+=(--team-yield-after-ms "$team_yield_after_ms")
  [ -z "$team_yellow$team_blue$team_both" ] || bridge_args+=(--team-output-dir "$log_dir")
  physics_args+=(--sync)
  radio_args+=(--sync --sync-clients "${sync_clients:-$clients}")
  # Team programs under the time shim: a stuck thread is named by the shim
  # (--team-grace); the radio's limit is for a team that computes that long.
  [ -n "$sync_timeout" ] || [ -z "$team_yellow$team_blue$team_both" ] || sync_timeout=30
  [ -z "$sync_timeout" ] || radio_args+=(--sync-timeout "$sync_timeout")
  [ "$sync_strict" = 1 ] && radio_args+=(--sync-strict)
  demo_args+=(--sync)
  bridge_args+=(--sync)
fi
[ -n "$duration" ] && physics_args+=(--duration "$duration")
referee_args=(auto --events "$log_dir/events.jsonl")
[ -n "$game_length" ] && referee_args+=(--game-length "$game_length")
# The teams' names go on REFEREE (both referees take the same two options).
team_name_args=()
[ -n "$yellow_name" ] && team_name_args+=(--yellow-name "$yellow_name")
[ -n "$blue_name" ] && team_name_args+=(--blue-name "$blue_name")
referee_args+=("${team_name_args[@]}")
[ "$repeat_games" = 1 ] && referee_args+=(--repeat)
[ "$tracked" = 1 ] && bridge_args+=(--tracked)
[ "$referee" = official ] && [ "$gc_ci" = 0 ] && bridge_args+=(--official-referee)
# The bridge's addresses and ports (set_ssl_ports); the defaults are left to it.
ssl_bridge_port_args() {
  bridge_args+=(--listen-address "$ssl_listen")
  if [ -n "$vision_port" ] || [ "$ssl_vision_port" != 10020 ]; then bridge_args+=(--vision-port "$ssl_vision_port"); fi
  [ -z "$vision_interface" ] || bridge_args+=(--vision-interface "$vision_interface")
  [ -z "$vision_ttl" ] || bridge_args+=(--vision-ttl "$vision_ttl")
  [ "$ssl_local_only" = 0 ] || bridge_args+=(--local-only)
  [ "$((10#$ssl_port_offset))" = 0 ] && return 0
  bridge_args+=(--control-port "$ssl_control_port" --blue-port "$ssl_blue_port" --yellow-port "$ssl_yellow_port"
    --tracked-port "$ssl_tracked_port" --referee-port "$ssl_referee_port" --grsim-port "$ssl_grsim_port"
    --grsim-blue-status-port "$ssl_grsim_blue_status" --grsim-yellow-status-port "$ssl_grsim_yellow_status")
}
ssl_bridge_port_args
if [ "$referee" = builtin ] && [ "$sync" = 1 ]; then
  # Physics steps only past states the referee judged (docs/autoref.md).
  physics_args+=(--sync-referee)
  referee_args+=(--sync)
fi
if [ "$gc_ci" = 1 ]; then
  # The link answers every state physics stops at, as the built-in referee does.
  physics_args+=(--sync-referee)
  referee_args=(--game-controller "$game_controller" --gc-dir "$log_dir/gc" --events "$log_dir/events.jsonl")
  [ -n "$game_length" ] && referee_args+=(--game-length "$game_length")
  referee_args+=("${team_name_args[@]}")
fi
start physics "${placement[@]}" "$bin_dir/ubersim_physics" "${common[@]}" "${physics_args[@]}" "${seed_args[@]}"
# wait_for_bus_claim PID: the rest starts once physics holds its bus (it claims
# it first thing), at most 2 s. Two launches at one instant both pass
# check_no_other_simulator; the loser's physics exits at once, and its
# emulators must never run on the winner's bus: the loser stops here.
wait_for_bus_claim() {
  [[ $lcm_url == udpm://* ]] || return 0
  for _ in $(seq 60); do
    if ! kill -0 "$1" 2>/dev/null; then
      wait "$1"
      local status=$? refused
      refused=$(grep -m 1 '^ubersim_physics: another ubersim_physics' "$log_dir/physics.log")
      if [ -n "$refused" ]; then
        echo "launch: $refused" >&2  # the same one line as check_no_other_simulator's
      else
        echo "launch: physics exited with status $status at start (see $log_dir/physics.log)" >&2
        why_failed physics "$status"
      fi
      [ "${names[0]}" != logger ] || { kill -TERM "${pids[0]}"; wait "${pids[0]}"; }
      exit 1
    fi
    # (Not a pipe into grep: with pipefail the check's exit 1 would hide grep's match.)
    [[ $("$bin_dir/ubersim_physics" --check-bus --lcm-url "$lcm_url" ${prefix:+--channel-prefix "$prefix"} 2>&1) == *"(pid $1)"* ]] &&
      return 0
    sleep 0.02
  done
}
wait_for_bus_claim "${pids[-1]}"
[ "$vision" = 1 ] && start vision "${placement[@]}" "$bin_dir/ubersim_vision" "${common[@]}" --profile "$profile" "${seed_args[@]}"
[ "$radio" = 1 ] && start radio "${placement[@]}" "$bin_dir/ubersim_radio" "${common[@]}" --profile "$profile" "${seed_args[@]}" "${radio_args[@]}"
# Sync mode: the radio emulator drops a client that stops answering, and logs
# each drop and rejoin on one line (docs/sync.md, "A dropped client"): shown
# here as it happens, by a tail of its log (--pid: it ends with this script)
# through a filter (ended and waited for before the summary at the end).
if [ "$sync" = 1 ] && [ "$radio" = 1 ]; then
  # Also what physics waits for, once a wait passes 2 s, and the time shim's
  # findings about the team programs (stuck threads, static programs) and
  # its hint when their polling makes the game slow.
  exec {sync_fd}> >(sed -un -e 's/^.*\(sync client \(dropped\|rejoined\): .*\)$/launch: radio: \1/p' \
    -e 's/^.*\(sync: physics waits .*\)$/launch: physics: \1/p' -e 's/^.*\] \(timeshim\( hint\)\?: .*\)$/launch: \1/p' >&2)
  sync_filter=$!
  sync_logs=("$log_dir/radio.log" "$log_dir/physics.log")
  [ "$ssl_bridge" = 0 ] || sync_logs+=("$log_dir/ssl_bridge.log")
  tail -q -n +1 -s 0.2 --pid=$$ -F "${sync_logs[@]}" >&"$sync_fd" 2>/dev/null &
  sync_watch=$!
fi
# start_referee PROGRAM LISTENING: starts the referee (ubersim's or the GC
# link). In sync mode it must hear the first state: the teams (whose
# registration lets physics start) come once its log says LISTENING (at most 20 s).
start_referee() {
  start referee "$bin_dir/$1" --lcm-url "$lcm_url" ${prefix:+--channel-prefix "$prefix"} "${referee_args[@]}"
  for _ in $(seq 200); do
    grep -q "$2" "$log_dir/referee.log" 2>/dev/null && break
    kill -0 "${pids[-1]}" 2>/dev/null || break  # it failed: the wait below reports it
    sleep 0.1
  done
}
[ "$referee" = builtin ] && start_referee ubersim_referee "automatic referee:"
[ "$gc_ci" = 1 ] && start_referee ubersim_gc_link "official game controller on"
for team in yellow blue; do
  if [ "$demo" = "$team" ] || [ "$demo" = both ]; then
    start "demo_$team" "$bin_dir/ubersim_demo_team" "${common[@]}" --team "$team" --mode "$demo_mode" "${demo_args[@]}"
  fi
done
[ "$ssl_bridge" = 1 ] && start ssl_bridge "$bin_dir/ubersim_ssl_bridge" "${common[@]}" "${bridge_args[@]}" "${seed_args[@]}"
# Without --sync a team program runs in real time next to the set.
if [ "$sync" = 0 ]; then
  [ -z "$team_yellow" ] || start_group team_yellow setsid sh -c "$(team_program "$team_yellow")"
  [ -z "$team_blue" ] || start_group team_blue setsid sh -c "$(team_program "$team_blue")"
  [ -z "$team_both" ] || start_group team_both setsid sh -c "$(team_program "$team_both")"
fi
[ "$viewer" = 1 ] && start viewer "$bin_dir/ubersim_viewer" "${common[@]}" --port "$viewer_port"
if [ "$open_viewer" = 1 ]; then
  if [ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "viewer:   no desktop session here (DISPLAY and WAYLAND_DISPLAY unset): open $viewer_url in a browser"
  elif ! command -v xdg-open >/dev/null 2>&1; then
    echo "viewer:   xdg-open is not installed: open $viewer_url in a browser"
  else
    # Open it once the viewer answers (at most 5 s), in a session of its own
    # so that the browser outlives Ctrl-C here.
    for _ in $(seq 50); do port_in_use "$viewer_port" && break; sleep 0.1; done
    setsid xdg-open "$viewer_url" >"$log_dir/xdg-open.log" 2>&1 </dev/null &
    echo "viewer:   opened in your browser (xdg-open $viewer_url)"
  fi
fi
physics_pid=${pids[1]:-}
[ -n "$log_file" ] || physics_pid=${pids[0]}
echo "channels: ${prefix}VISION ${prefix}VISION_GEOMETRY ${prefix}RADIO_YELLOW ${prefix}RADIO_BLUE ${prefix}RADIO_FEEDBACK_YELLOW ${prefix}RADIO_FEEDBACK_BLUE ${prefix}SIM_STATE ${prefix}SIM_CONTROL"
echo "watch:    tools/lcm-spy.sh -l '$lcm_url'      control: build/bin/ubersim_referee --help"
[ "$referee" = builtin ] && echo "referee:  automatic, on ${prefix}REFEREE; event log $log_dir/events.jsonl"
[ "$gc_ci" = 1 ] && echo "referee:  the official game controller in CI mode (sim time), on ${prefix}REFEREE; its log $log_dir/gc/gc.log; event log $log_dir/events.jsonl"
[ "$referee" = official ] && [ "$gc_ci" = 0 ] && echo "referee:  the official game controller's Referee on 224.5.23.1:$ssl_referee_port, forwarded to ${prefix}REFEREE"
[ "$ssl_bridge" = 1 ] && print_ssl_ports
[ "$vision" = 0 ] && echo "vision:   not started: a real vision server must publish ${prefix}VISION"
[ "$radio" = 0 ] && echo "radio:    not started: a real radio server must listen on ${prefix}RADIO_YELLOW / ${prefix}RADIO_BLUE"
echo "Ctrl-C stops everything."

while :; do
  finished=""
  wait -n -p finished "${pids[@]}"
  status=$?
  [ -n "$finished" ] || continue  # interrupted by a signal: the trap handles it
  for i in "${!pids[@]}"; do
    [ "${pids[$i]}" = "$finished" ] || continue
    name=${names[$i]}
    # A group stays listed: what its first process started is stopped with the rest.
    if [ "${groups[$i]}" = 0 ]; then
      unset 'pids[i]' 'names[i]' 'groups[i]'
      pids=("${pids[@]}") names=("${names[@]}") groups=("${groups[@]}")
    fi
    if [ "$finished" = "$physics_pid" ] && [ "$status" = 0 ] && [ -n "$duration" ]; then
      echo "launch: physics finished its $duration s of sim time: stopping the rest"
    elif [ "$name" = referee ] && [ "$status" = 0 ]; then
      echo "launch: the game is over ($(grep '^result' "$log_dir/referee.log" | tail -1)): stopping the rest"
    else
      echo "launch: $name exited with status $status: stopping the rest (see $log_dir/$name.log)" >&2
      why_failed "$name" "$status"
      failed=1
    fi
    break
  done
  trap '' INT TERM
  stop_all
  exit $failed
done
