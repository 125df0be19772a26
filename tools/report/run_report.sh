#!/usr/bin/env bash
# Runs the whole fidelity and speed report and writes OUT_DIR/report.md with
# its figures (PNG, gnuplot) and data files beside it.
#
#   tools/report/run_report.sh OUT_DIR [--build DIR] [--quick] [--cpu-seconds S]
#                              [--skip-fidelity] [--skip-bench] [--skip-cpu]
#
#   --build DIR       build folder with bin/ (default: build, or $UBERSIM_BUILD_DIR)
#   --quick           a smoke run: fewer trials, sweep points, kicks and laps;
#                     a short benchmark; 5 s CPU windows (figures are rougher)
#   --cpu-seconds S   CPU-share window per scenario (default 30 s of wall time)
#   --notes FILE      markdown put under the targets table (e.g. what causes a
#                     missed target, found by looking into it)
#
# The experiments run the real ubersim_physics / _vision / _radio over LCM in
# a network namespace of their own (tests/run_isolated.sh), so a simulation
# already running on this machine neither disturbs them nor is disturbed.
# Needs gnuplot (tools/install-deps.sh installs gnuplot-nox).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${UBERSIM_BUILD_DIR:-$root/build}
out=""
quick=0
cpu_seconds=30
do_fidelity=1
do_bench=1
do_cpu=1
notes=""
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --quick) quick=1; cpu_seconds=5; shift ;;
    --cpu-seconds) cpu_seconds=$2; shift 2 ;;
    --notes) notes=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); shift 2 ;;
    --skip-fidelity) do_fidelity=0; shift ;;
    --skip-bench) do_bench=0; shift ;;
    --skip-cpu) do_cpu=0; shift ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    -*) echo "run_report.sh: unknown option $1" >&2; exit 2 ;;
    *) out=$1; shift ;;
  esac
done
if [ -z "$out" ]; then
  echo "usage: run_report.sh OUT_DIR [--build DIR] [--quick] [--cpu-seconds S]" >&2
  exit 2
fi
bin=$build/bin
for program in ubersim_physics ubersim_vision ubersim_radio ubersim_demo_team \
               ubersim_physics_bench ubersim_report_fidelity ubersim_report_cpu; do
  if [ ! -x "$bin/$program" ]; then
    echo "run_report.sh: $bin/$program is missing: build first (tools/build.sh)" >&2
    exit 2
  fi
done
command -v gnuplot >/dev/null || { echo "run_report.sh: gnuplot is not installed" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
isolated=$root/tests/run_isolated.sh
started=$(date +%s)

fidelity_status=0
if [ $do_fidelity = 1 ]; then
  echo "== fidelity experiments (acceleration, figure-8, ball) -> $out"
  args=(--out "$out")
  [ $quick = 1 ] && args+=(--quick --trials 2)
  "$isolated" report_fidelity "$bin/ubersim_report_fidelity" "${args[@]}" || fidelity_status=$?
  if [ $fidelity_status != 0 ] && [ $fidelity_status != 3 ]; then
    echo "run_report.sh: the fidelity experiments failed (exit $fidelity_status)" >&2
    exit 1
  fi
fi

if [ $do_bench = 1 ]; then
  echo "== physics benchmark (ubersim_physics_bench)"
  bench_args=()
  [ $quick = 1 ] && bench_args+=(--seconds 5 --repeat 1)
  "$bin/ubersim_physics_bench" "${bench_args[@]}" | tee "$out/bench.txt"
  # Its table rows: scenario, NxM, model, server, world, bare ODE, overhead.
  awk '$3 ~ /^(jointed|planar)$/ && $2 ~ /^[0-9]+x[0-9]+$/ {
         sub(/%/, "", $7); print $1, $2, $3, $4, $5, $6, $7 }' "$out/bench.txt" \
    > "$out/bench.dat"
fi

if [ $do_cpu = 1 ]; then
  echo "== CPU share in real time (${cpu_seconds} s per scenario)"
  "$isolated" report_cpu "$bin/ubersim_report_cpu" --out "$out" --seconds "$cpu_seconds"
fi

echo "== figures (gnuplot)"
(
  cd "$here/plots"
  for script in ramp saturation figure8 ball bench cpu; do
    case $script in
      ramp) grep -qs '^ramp_count = [1-9]' "$out/values.gp" || continue ;;
      saturation) grep -qs '^sweep_count = [1-9]' "$out/values.gp" || continue ;;
      figure8) grep -qs '^figure8_count = [1-9]' "$out/values.gp" || continue ;;
      ball) [ -f "$out/kicks.dat" ] || continue ;;
      bench) [ -s "$out/bench.dat" ] || continue ;;
      cpu) [ -s "$out/cpu.dat" ] || continue ;;
    esac
    gnuplot -e "dir='$out'" "$script.gp"
  done
)

echo "== report.md"
# When and where the measurements were made (kept when only re-assembling:
# all three --skip-* options re-plot and re-write report.md from the files).
if [ $do_fidelity = 1 ] || [ $do_bench = 1 ] || [ $do_cpu = 1 ]; then
  commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
  git -C "$root" diff --quiet HEAD 2>/dev/null || commit="$commit (with uncommitted changes)"
  cpu_model=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')
  {
    echo "Generated $(date -u '+%Y-%m-%d %H:%M UTC') on $(nproc) cores of ${cpu_model:-unknown CPU},"
    echo "commit $commit, in $(( $(date +%s) - started )) s$([ $quick = 1 ] && echo ' (--quick: a smoke run, rougher figures)')."
  } > "$out/run_info.md"
fi
{
  echo "# ubersim: fidelity and speed report"
  echo
  [ -f "$out/run_info.md" ] && cat "$out/run_info.md"
  echo "Regenerate with \`tools/report/run_report.sh OUT_DIR\` (\`--help\` for its options)."
  echo
  echo "The paper judged ÜberSim by putting the simulated robot beside the real one. Here the"
  echo "simulation stands beside the physics its configs claim: every prediction below is"
  echo "worked out from the config files alone, and every measurement goes the way a team's"
  echo "software goes: radio commands on \`RADIO_YELLOW\` into the real radio emulator, real"
  echo "physics, detections read back from the real vision emulator on \`VISION\`, with ground"
  echo "truth (\`SIM_STATE\`) beside them. Physics runs in lockstep, so the experiments are exact"
  echo "in simulation time whatever the load on the machine; the speed section is wall time."
  echo
  echo "## Targets"
  echo
  echo "| target | measured | detail | |"
  echo "|---|---|---|---|"
  [ -f "$out/targets_fidelity.md" ] && cat "$out/targets_fidelity.md"
  [ -f "$out/targets_cpu.md" ] && cat "$out/targets_cpu.md"
  if [ -f "$out/bench.dat" ]; then
    awk '$1 == "division_a_11v11" {
           target = ($3 == "jointed") ? 12 : 100
           printf "| Physics benchmark 2 x 11 %s at 240 Hz at least %dx real time (physics issue) | %.1fx | as fast as possible, SIM_STATE published | %s |\n",
                  $3, target, $4, ($4 >= target) ? "met" : "**MISSED**"
           printf "| Physics benchmark 2 x 11 %s: overhead over bare ODE under 15 %% (physics issue) | %+.1f %% | server %.1fx, bare ODE %.1fx | %s |\n",
                  $3, $7, $4, $6, ($7 < 15) ? "met" : "**MISSED**"
         }' "$out/bench.dat"
  fi
  echo
  if [ -n "$notes" ]; then
    cat "$notes"
    echo
  fi
  [ -f "$out/fidelity.md" ] && cat "$out/fidelity.md"
  if [ -f "$out/bench.dat" ] || [ -f "$out/cpu.md" ]; then
    echo "## 4. Speed"
    echo
  fi
  if [ -f "$out/bench.dat" ]; then
    echo "### Physics benchmark"
    echo
    echo "\`ubersim_physics_bench\` (the physics engineer's program; its own output is in"
    echo "[bench.txt](bench.txt)): simulated seconds per wall second at 240 Hz, as fast as"
    echo "possible, with SIM_STATE published every step, beside the same scene stepped by bare"
    echo "ODE in the same run. Targets from the physics issue (2 x 11): jointed >= 12x, planar"
    echo ">= 100x, overhead under 15 %. For scale: the best-known simulator of this league"
    echo "reaches 2.6x real time for 2 x 11 here."
    echo
    echo "| scenario | robots | model | server (x real time) | world alone | bare ODE | overhead over bare ODE |"
    echo "|---|---|---|---|---|---|---|"
    awk '{ printf "| %s | %s | %s | %.1f | %.1f | %.1f | %+.1f %% |\n", $1, $2, $3, $4, $5, $6, $7 }' "$out/bench.dat"
    echo
    echo "![Physics benchmark](bench.png)"
    echo
  fi
  [ -f "$out/cpu.md" ] && cat "$out/cpu.md"
  echo "## Files"
  echo
  echo "Data behind every figure: \`*.dat\` (whitespace-separated, headers in \`#\` lines; trials"
  echo "as gnuplot data blocks), predictions in \`values.gp\`; the processes' logs and the config"
  echo "files the experiments wrote (scenarios, the roll-out hall, vision profiles with the"
  echo "lockstep marker camera) in \`work/\`. The example report in the repository (docs/example_report/)"
  echo "keeps the text and figures only; its data files are regenerated by"
  echo "\`tools/report/run_report.sh OUT_DIR\`."
} > "$out/report.md"
echo "report: $out/report.md"
if [ $fidelity_status = 3 ]; then
  echo "run_report.sh: some fidelity targets were missed (see the report)" >&2
fi
