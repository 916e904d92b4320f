#!/usr/bin/env bash
# Fuzzes the mesh reader for heap damage inside Assimp (make fuzz-heap SEEDS="2 3 ...", which
# first builds fuzz_mesh without sanitizers in build-fuzz-heap/).
#
#   tools/fuzz-heap.sh BUILD_DIR RUNS SEED...
#
# Assimp is not built with AddressSanitizer, so ASan (make sanitize) sees Assimp's writes past
# a heap block only when its allocator later reuses the damaged chunk, runs or a whole process
# later, with no input to show for it. Here BUILD_DIR's fuzz_mesh, built without ASan, runs
# under glibc's heap checks (libc_malloc_debug, MALLOC_CHECK_=3), which check a chunk when it is
# freed, inside the import that damaged it: the run aborts while the file being read is still
# the harness's temporary file, which is kept. Each seed runs RUNS executions on a copy of the
# committed corpus; a crash, an abort, a hang (over 10 s on one input) or a memory blow-up
# (over 4 GiB) fails it. See docs/architecture.md, "Sanitizers and fuzzing".
set -euo pipefail
[[ $# -ge 3 ]] || { echo "usage: $0 BUILD_DIR RUNS SEED..." >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1 runs=$2
shift 2
build=$(cd "$build" && pwd)
debug=$(ls /usr/lib/*/libc_malloc_debug.so.0 | head -1)
artifacts="$build/fuzz-heap-artifacts"
mkdir -p "$artifacts"
failed=0
for seed in "$@"; do
  work=$(mktemp -d)
  scratch=$(mktemp -d)  # the harness's TMPDIR: its per-process input folders, removed below
  cp "$root/tests/fuzz/corpus/mesh/"* "$work/"
  log="$build/fuzz-heap-$seed.log"
  # -handle_abrt=0: glibc's abort on a damaged heap ends the process at once (libFuzzer's own
  # handler would allocate on that heap and hang).
  TMPDIR="$scratch" LD_PRELOAD="$debug" MALLOC_CHECK_=3 timeout -k 10 1800 "$build/bin/fuzz_mesh" -seed="$seed" \
    -runs="$runs" -timeout=10 -rss_limit_mb=4096 -handle_abrt=0 \
    "-artifact_prefix=$artifacts/seed-$seed-" "$work" >"$log" 2>&1 &
  pid=$!
  if wait $pid; then
    echo "fuzz_mesh seed $seed: $runs executions, no heap damage, crash, hang or blow-up"
  else
    failed=1
    # The harness writes each input to wavetrace-fuzz-mesh-<pid>/ in its TMPDIR.
    kept=$(ls -d "$scratch/wavetrace-fuzz-mesh-"* 2>/dev/null || true)
    [[ -n "$kept" ]] && cp -r "$kept" "$artifacts/seed-$seed-input"
    echo "fuzz_mesh seed $seed: FAILED (log: $log; inputs in $artifacts)" >&2
    grep -E "ERROR|SUMMARY|free\(\)|corrupted|malloc\(\)|Test unit written" "$log" | head -5 >&2
  fi
  rm -rf "$work" "$scratch"
done
exit $failed
