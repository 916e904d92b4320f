#!/usr/bin/env bash
# Runs the sanitized build's tests (make sanitize) as JOBS gtest shards side by side: the
# sanitized tests are mostly single-threaded, so one process per core halves CI's wall time.
#
#   tools/run-sanitized-tests.sh BUILD_DIR JOBS FILTER
#
# Each shard's output goes to BUILD_DIR/sanitized-tests-N.log; a failing shard's log is printed.
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: $0 BUILD_DIR JOBS FILTER" >&2; exit 2; }
build=$(cd "$1" && pwd)
jobs=$2 filter=$3
root=$(cd "$(dirname "$0")/.." && pwd)
export LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp"
export GTEST_TOTAL_SHARDS=$jobs
pids=()
for ((shard = 0; shard < jobs; ++shard)); do
  GTEST_SHARD_INDEX=$shard "$build/bin/wavetrace_tests" --gtest_filter="$filter" --gtest_brief=1 \
    >"$build/sanitized-tests-$shard.log" 2>&1 &
  pids+=($!)
done
failed=0
for ((shard = 0; shard < jobs; ++shard)); do
  if ! wait "${pids[$shard]}"; then
    echo "sanitized tests, shard $shard of $jobs: FAILED" >&2
    cat "$build/sanitized-tests-$shard.log" >&2
    failed=1
  fi
done
[[ $failed -eq 0 ]] || exit 1
passed=$(cat "$build"/sanitized-tests-*.log | sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\?\./\1/p' |
         awk '{ s += $1 } END { print s + 0 }')
skipped=$(cat "$build"/sanitized-tests-*.log | sed -n 's/^\[  SKIPPED \] \([0-9]*\) tests\?[.,].*/\1/p' |
          awk '{ s += $1 } END { print s + 0 }')
echo "sanitized tests: $passed passed, $skipped skipped in $jobs shards (logs: $build/sanitized-tests-*.log)"
