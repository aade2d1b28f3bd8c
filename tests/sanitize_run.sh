#!/usr/bin/env bash
# Runs the test suite of a sanitizer build (make sanitize) in one process per core instead of
# one per test case: strand_tests under ASan takes 0.7 s to start, which over ~1,000 cases was
# most of the suite's time. GoogleTest's own sharding splits the cases; the cases listed in
# tests/sanitize_skip.txt are left out (they run in `make test`). Any sanitizer report aborts
# its shard (abort_on_error) and fails the run; the shard's log is printed.
# Usage: tests/sanitize_run.sh BUILD_DIR [SHARDS]
set -uo pipefail
build="$1"
shards="${2:-$(nproc)}"
src="$(cd "$(dirname "$0")/.." && pwd)"
exe="$build/tests/strand_tests"
skip="$(grep -v -e '^#' -e '^$' "$src/tests/sanitize_skip.txt" | cut -d' ' -f1 | paste -sd:)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$src/tests/fuzz/lsan.supp:print_suppressions=0"
rm -f "$build"/sanitize-shard-*.log
start=$SECONDS
pids=()
for ((i = 0; i < shards; i++)); do
  GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i \
    "$exe" --gtest_filter="-$skip" >"$build/sanitize-shard-$i.log" 2>&1 &
  pids+=($!)
done
failed=0
for ((i = 0; i < shards; i++)); do
  if ! wait "${pids[$i]}"; then
    failed=1
    echo "sanitize: shard $i of $shards failed; its log ($build/sanitize-shard-$i.log):"
    tail -n 80 "$build/sanitize-shard-$i.log"
  fi
done
passed=$(cat "$build"/sanitize-shard-*.log | grep -E '^\[  PASSED  \] [0-9]+' | awk '{s += $4} END {print s + 0}')
echo "sanitize: $passed test cases passed in $shards shards, $((SECONDS - start)) s" \
     "($(grep -vc -e '^#' -e '^$' "$src/tests/sanitize_skip.txt") left to make test, tests/sanitize_skip.txt)"
exit $failed
