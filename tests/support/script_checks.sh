# The checks of a test script, sourced by it: fail WHAT counts a failure and
# says it; finish WORK ends the test (exit 1 naming WORK, where its outputs
# stay, after a failure; else WORK removed and PASS); processes_of_this_test.
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
finish() {
  if [ "$failures" != 0 ]; then
    echo "$failures failure(s); outputs in $1"
    exit 1
  fi
  rm -rf "$1"
  echo PASS
  exit 0
}
# The processes whose command line holds the script's $marker (every process
# it started has it), but not the script itself.
processes_of_this_test() { pgrep -f -- "$marker" | grep -v "^$$\$" || true; }
