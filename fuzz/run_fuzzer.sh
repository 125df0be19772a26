#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time.
# Usage: run_fuzzer.sh FUZZER SECONDS SEED_DIR... [-- LIBFUZZER_OPTIONS...]
# The corpus it grows goes to $UBERSIM_FUZZ_CORPUS/<fuzzer> when that is set
# (tools/fuzz.sh keeps it between runs), else to a temporary folder removed on
# success. Seed folders are only read. A crashing, hanging or memory-hungry
# input is kept and its path printed: add it to tests/data/fuzz_regressions/.
set -uo pipefail
fuzzer=$1
seconds=$2
shift 2
seeds=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  [ -d "$1" ] && seeds+=("$1")
  shift
done
[ "${1:-}" = "--" ] && shift
name=$(basename "$fuzzer")
work=$(mktemp -d "${TMPDIR:-/tmp}/ubersim-$name.XXXXXX")
if [ -n "${UBERSIM_FUZZ_CORPUS:-}" ]; then
  corpus="$UBERSIM_FUZZ_CORPUS/$name"
else
  corpus="$work/corpus"
fi
mkdir -p "$corpus"
# 64 MB for any one allocation: no input of ours (at most a 64 KB datagram)
# has a reason to ask for more, so a larger one is the bug the issue is about
# (and, unlike a timeout, it is found the same on a loaded machine). Not
# lower: protobuf 3.21 reserves up to 50 MB for a field longer than its input,
# and the SSL bridge's Any payloads (ER-Force realism, robot specs) are still
# parsed by protobuf alone (docs/fuzzing.md). 30 s per
# input: a busy machine at nice 19 stalls for seconds; real hangs are forever.
"$fuzzer" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -malloc_limit_mb=64 \
  -print_final_stats=1 -artifact_prefix="$work/" "$@" "$corpus" "${seeds[@]}" \
  >"$work/log" 2>&1
status=$?
grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb)' "$work/log" || true
if [ $status -ne 0 ]; then
  tail -n 60 "$work/log"
  echo "run_fuzzer: $name failed (exit $status); inputs and log kept in $work" >&2
  exit 1
fi
rm -rf "$work"
