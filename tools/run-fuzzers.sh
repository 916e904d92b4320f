#!/usr/bin/env bash
# Runs the libFuzzer targets of a sanitized build (make sanitize, make fuzz).
#
#   tools/run-fuzzers.sh BUILD_DIR --runs N      what CI runs: N executions per target from a
#                                                fixed seed, on a copy of the committed corpus
#                                                (the same inputs every time); FUZZ_XML_RUNS,
#                                                FUZZ_IMAGE_RUNS, ... in the environment set a
#                                                target's own count
#   tools/run-fuzzers.sh BUILD_DIR --seconds S   explore for S seconds per target and merge the
#                                                inputs that grow coverage into tests/fuzz/corpus
#
# Any crash, sanitizer report, leak (LSan; see tests/fuzz/lsan.supp), hang (over 10 s on one
# input) or memory blow-up (over 4 GiB) fails the run; the input is kept in BUILD_DIR/fuzz-artifacts.
set -euo pipefail
[[ $# -eq 3 && ( "$2" == "--runs" || "$2" == "--seconds" ) ]] ||
  { echo "usage: $0 BUILD_DIR --runs N | --seconds S" >&2; exit 2; }
build=$(cd "$1" && pwd)
mode=$2 amount=$3
root=$(cd "$(dirname "$0")/.." && pwd)
export LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp"
mkdir -p "$build/fuzz-artifacts"
# Inputs up to 64 KiB: room for the nesting attacks (a chain of 1,100 glTF nodes is ~25 KB)
# that libFuzzer's default cap, the corpus's largest input, would keep out of reach.
common=(-seed=1 -timeout=10 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1
        "-artifact_prefix=$build/fuzz-artifacts/")
# One target per process, all side by side (each is single-threaded); each reports to its own
# file, printed in order once all are done.
fuzz_one() {
  # `work` and `scratch` are global: the EXIT trap of this function's subshell still needs
  # them. The targets write their inputs under TMPDIR (wavetrace-fuzz-TARGET-PID/): a folder of
  # this run's own, removed with it.
  local target=$1 log start runs cov before
  work=$(mktemp -d)
  scratch=$(mktemp -d)
  trap 'rm -rf "$work" "$scratch"' EXIT
  export TMPDIR="$scratch"
  log="$build/fuzz-$target.log"
  if [[ "$mode" == "--runs" ]]; then
    cp "$root/tests/fuzz/corpus/$target/"* "$work/"
    local runs_here=$amount own="FUZZ_${target^^}_RUNS"
    [[ -n "${!own:-}" ]] && runs_here=${!own}
    args=("$work" -runs="$runs_here")
  else
    args=("$work" "$root/tests/fuzz/corpus/$target" -max_total_time="$amount")
  fi
  start=$(date +%s)
  if ! "$build/bin/fuzz_$target" "${common[@]}" "${args[@]}" >"$log" 2>&1; then
    echo "fuzz_$target: FAILED (log: $log); the input is in $build/fuzz-artifacts/:"
    grep -E "ERROR|SUMMARY|runtime error|assert|Test unit written" "$log" | head -20
    return 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1)
  echo "fuzz_$target: $runs executions in $(( $(date +%s) - start )) s, $cov, no crash, hang or leak"
  if [[ "$mode" == "--seconds" ]]; then
    # Keep only what adds coverage: merge the session's inputs into the committed corpus.
    before=$(ls "$root/tests/fuzz/corpus/$target" | wc -l)
    "$build/bin/fuzz_$target" -merge=1 "${common[@]}" "$root/tests/fuzz/corpus/$target" "$work" \
      >>"$log" 2>&1
    echo "fuzz_$target: corpus $before -> $(ls "$root/tests/fuzz/corpus/$target" | wc -l) inputs"
  fi
}
targets=(scene xml pbrt mesh film image volume)
pids=()
for target in "${targets[@]}"; do
  ( fuzz_one "$target" ) >"$build/fuzz-$target.summary" 2>&1 &
  pids+=($!)
done
failed=0
for i in "${!targets[@]}"; do
  wait "${pids[$i]}" || failed=1
  cat "$build/fuzz-${targets[$i]}.summary"
done
exit $failed
