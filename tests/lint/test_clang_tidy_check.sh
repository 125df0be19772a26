#!/usr/bin/env bash
# check_clang_tidy.py itself, on a small tree made here: it must fail and name
# file:line:check for a finding in a translation unit and in one of our
# headers, must not report generated code in the build folder, and must pass
# once the findings are gone. Units with the same flags are checked as one batch:
# unit.cpp and other.cpp share one; twin_a.cpp and twin_b.cpp (other flags) define
# the same name, so their batch does not compile and twin_b is checked apart from twin_a.
# Skipped (77) when clang-tidy is not installed.
# Usage: test_clang_tidy_check.sh PYTHON CHECK_CLANG_TIDY_PY
set -uo pipefail
python=$1
checker=$2
if ! command -v clang-tidy >/dev/null 2>&1; then
  echo "test_clang_tidy_check: skipped, clang-tidy is not installed (tools/install-deps.sh installs it)"
  exit 77
fi
tree=$(mktemp -d "${TMPDIR:-/tmp}/clang-tidy-check.XXXXXX")
mkdir -p "$tree/src" "$tree/include" "$tree/build/generated"
printf '%s\n' "Checks: '-*,modernize-use-nullptr'" >"$tree/.clang-tidy"
printf '%s\n' '#pragma once' 'inline int* in_header() { return 0; }' >"$tree/include/ours.hpp"
printf '%s\n' '#pragma once' 'inline int* generated() { return 0; }' >"$tree/build/generated/gen.hpp"
printf '%s\n' '#include "ours.hpp"' '#include "gen.hpp"' '' 'int* in_unit() { return 0; }' >"$tree/src/unit.cpp"
printf '%s\n' 'int* in_other() { return 0; }' >"$tree/src/other.cpp"
for twin in twin_a twin_b; do
  printf '%s\n' 'namespace { int* twin() { return 0; } }' "int* $twin() { return twin(); }" \
    >"$tree/src/$twin.cpp"
done
entry() {  # entry FILE DEFINE: a compile_commands.json entry
  printf '{"directory": "%s", "file": "%s",\n "command": "c++ -std=c++17 %s -I%s -I%s -c %s"}' \
    "$tree/build" "$tree/src/$1" "$2" "$tree/include" "$tree/build/generated" "$tree/src/$1"
}
printf '[%s,\n%s,\n%s,\n%s]\n' "$(entry unit.cpp -DONE)" "$(entry other.cpp -DONE)" \
  "$(entry twin_a.cpp -DTWO)" "$(entry twin_b.cpp -DTWO)" >"$tree/build/compile_commands.json"

failures=0
expect() {  # expect DESCRIPTION GREP_PATTERN: the checker's last output holds the pattern
  if ! grep -qE "$2" "$tree/out"; then
    echo "FAIL: $1 (no line matching '$2')"
    failures=$((failures + 1))
  fi
}

"$python" "$checker" "$tree" "$tree/build" >"$tree/out" 2>&1
status=$?
cat "$tree/out"
[ "$status" -eq 1 ] || { echo "FAIL: exit status $status on findings, expected 1"; failures=$((failures + 1)); }
expect "finding in the translation unit" '^src/unit\.cpp:4: modernize-use-nullptr: '
expect "finding in our header" '^include/ours\.hpp:2: modernize-use-nullptr: '
expect "finding in the second unit of a batch" '^src/other\.cpp:1: modernize-use-nullptr: '
expect "finding in a unit of a batch that did not compile" '^src/twin_a\.cpp:1: modernize-use-nullptr: '
expect "finding in its twin" '^src/twin_b\.cpp:1: modernize-use-nullptr: '
expect "every unit checked: one batch, and the twins' batch split in two" ' 0 translation units clang-tidy could not check, 4 translation units checked in 4 runs'
if grep -q 'gen\.hpp' "$tree/out"; then
  echo "FAIL: reported generated code in the build folder"
  failures=$((failures + 1))
fi

sed -i 's/return 0;/return nullptr;/' "$tree"/src/*.cpp "$tree/include/ours.hpp"
"$python" "$checker" "$tree" "$tree/build" >"$tree/out" 2>&1
status=$?
cat "$tree/out"
[ "$status" -eq 0 ] || { echo "FAIL: exit status $status on a clean tree, expected 0"; failures=$((failures + 1)); }
expect "summary on a clean tree" '^check_clang_tidy: 0 findings in 0 files'

if [ "$failures" -ne 0 ]; then
  echo "test_clang_tidy_check: $failures failures (tree kept in $tree)"
  exit 1
fi
rm -rf "$tree"
echo "test_clang_tidy_check: the checker fails on findings, names file:line:check, passes when clean"
