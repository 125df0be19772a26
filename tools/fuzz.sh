#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang, in build-fuzz/) and runs them.
# Usage: tools/fuzz.sh [SECONDS] [TARGET...]   run each target SECONDS (default 600)
#        tools/fuzz.sh --build                 only build them
# Targets run side by side at nice 19, each growing its corpus in
# build-fuzz/corpus/<target>/ (kept between runs, never committed). A finding
# stops that target and prints where its input was kept; see docs/fuzzing.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${UBERSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
# -O1 for campaigns; tools/test.sh's short runs build -O0 in a folder of their own.
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DUBERSIM_FUZZ=ON -DCMAKE_BUILD_TYPE=Release \
  -DUBERSIM_FUZZ_OPTIMIZATION="${UBERSIM_FUZZ_OPTIMIZATION:--O1}" "${launcher[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzzers
[ "${1:-}" = "--build" ] && exit 0

seconds=${1:-600}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=($(cd "$build/bin" && ls fuzz_* 2>/dev/null))
fi
export UBERSIM_FUZZ_CORPUS="$build/corpus"
seeds="$build/fuzz/seeds"
pids=()
for target in "${targets[@]}"; do
  extra=()
  [ "$target" = fuzz_config ] && extra=("$root/config")
  echo "fuzz: $target for ${seconds}s (corpus $UBERSIM_FUZZ_CORPUS/$target)"
  nice -n 19 "$root/fuzz/run_fuzzer.sh" "$build/bin/$target" "$seconds" "$seeds/$target" \
    "${extra[@]}" >"$build/$target.last.log" 2>&1 &
  pids+=($!)
done
failed=0
for i in "${!pids[@]}"; do
  if wait "${pids[$i]}"; then
    echo "fuzz: ${targets[$i]}: no finding; $(grep -h 'number_of_executed_units' "$build/${targets[$i]}.last.log")"
  else
    failed=1
    echo "fuzz: ${targets[$i]}: FINDING, see $build/${targets[$i]}.last.log"
  fi
done
exit $failed
