#!/usr/bin/env bash
# The dependency check must pass on the tree as committed and fail, naming the package and the
# file, when a package the build needs is dropped from tools/install-deps.sh's list.
#   tests/check_deps_test.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
src=$1 build=$2
check="$src/tools/check-deps.sh"
fail() { echo "FAIL: $*"; exit 1; }

out=$("$check" "$build" 2>&1) || fail "the check fails on the committed list:"$'\n'"$out"
echo "as committed: passes"

# name of the package dropped (and, after commas, packages that would pull it in, dropped with
# it), then a file the check must name as coming from it
cases=(
  "openimageio-tools /usr/bin/iconvert"                    # the bug of issue 8: an imported tool
  "libfmt-dev /usr/include/fmt/core.h"                     # a header the compiler read
  "zlib1g-dev,python3-dev,python3-matplotlib /usr/lib/x86_64-linux-gnu/libz.so"  # a library on a link line
)
for c in "${cases[@]}"; do
  read -r pkgs file <<<"$c"
  IFS=, read -ra dropped <<<"$pkgs"
  pkg=${dropped[0]}
  args=()
  for p in "${dropped[@]}"; do args+=(--without "$p"); done
  out=$("$check" "$build" "${args[@]}" 2>&1)
  rc=$?
  [[ $rc -eq 1 ]] || fail "without $pkg: exit $rc, expected 1"$'\n'"$out"
  grep -qF "$file" <<<"$out" || fail "without $pkg: $file not reported"$'\n'"$out"
  grep -q "): $pkg\$" <<<"$out" || fail "without $pkg: the package is not named"$'\n'"$out"
  echo "without $pkg: fails and names $file"
done
