#!/usr/bin/env bash
# Lint as a test: every C++ file git tracks is formatted as the repository's
# .clang-format says. Prints each file that is not, with the first lines
# clang-format would change, and fails. Fix with:
#   git ls-files '*.cpp' '*.hpp' '*.h' '*.cc' | xargs clang-format -i
# Usage: check_clang_format.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
cd "$source_dir"
if ! command -v clang-format >/dev/null 2>&1; then
  echo "check_clang_format: clang-format is not installed (tools/install-deps.sh installs it)" >&2
  exit 1
fi
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "check_clang_format: skipped, $source_dir is not a git work tree (nothing says which files are ours)"
  exit 77
fi
checked=0
failing=0
while IFS= read -r file; do
  [ -f "$file" ] || continue  # deleted in the work tree, not yet committed
  checked=$((checked + 1))
  if ! clang-format --dry-run --Werror "$file" 2>"$TMPDIR/clang-format.out"; then
    failing=$((failing + 1))
    echo "not formatted: $file"
    head -n 6 "$TMPDIR/clang-format.out" | sed 's/^/    /'
  fi
done < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.cc')
rm -f "$TMPDIR/clang-format.out"
echo "check_clang_format: $failing of $checked C++ files not formatted"
[ "$failing" -eq 0 ]
