#!/usr/bin/env bash
# Fails when a configured and built tree uses a file from a Debian package that
# tools/install-deps.sh neither installs nor pulls in through hard dependencies.
#
#   tools/check-deps.sh BUILD_DIR [--without PACKAGE]...
#
# A machine that already has a package installed by hand builds and tests fine without it,
# so CI on such a machine cannot see a missing install step (issue 8: openimageio-tools).
# This check looks at what the build really used, not at what the machine has:
#   - every CMake file that configure read (CMakeFiles/Makefile.cmake),
#   - every file that our dependencies' imported targets name (locations of libraries and
#     tools, include directories, link items; written by cmake/ReferencedFiles.cmake),
#   - every header the compiler read (the *.o.d depfiles),
#   - every library on a link line (link.txt, with -lNAME resolved as the linker would), and
#     what the compiler driver adds to the link by itself (crt files, libstdc++, sanitizer and
#     libFuzzer runtimes; asked of the driver with -###),
#   - every shared library the built programs load (ldd),
#   - the tools the build and the tests run (compiler, make, cmake, ctest, and the commands
#     the checks themselves call).
# Each file is mapped to the package that owns it (dpkg's file lists), and each package must
# lie in the closure of install-deps.sh's packages under Depends and Pre-Depends (not
# Recommends or Suggests: we install with --no-install-recommends), or be part of every
# Debian system (Essential: yes or Priority: required). The closure is computed from dpkg's
# status database, so it needs no apt lists. --without drops a package from install-deps.sh's
# list, which is how the test of this check shows it catching a missing package.
set -euo pipefail

usage() { echo "usage: $0 BUILD_DIR [--without PACKAGE]..." >&2; exit 2; }
[[ $# -ge 1 ]] || usage
build=$(cd "$1" && pwd) || usage
shift
without=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --without) [[ $# -ge 2 ]] || usage; without+=("$2"); shift 2 ;;
    *) usage ;;
  esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

[[ -f "$build/CMakeCache.txt" ]] || { echo "check-deps: $build is not a configured build" >&2; exit 2; }
[[ -f "$build/referenced-files.txt" ]] ||
  { echo "check-deps: $build/referenced-files.txt is missing (cmake/ReferencedFiles.cmake)" >&2; exit 2; }

# ---- 1. the files the build used, as "what<TAB>path" ----
refs="$tmp/refs"
: >"$refs"

# CMake files read at configure time.
sed -n '/^set(CMAKE_MAKEFILE_DEPENDS/,/^)/p' "$build/CMakeFiles/Makefile.cmake" |
  grep -o '"/[^"]*"' | tr -d '"' | sed 's/^/cmake file read at configure\t/' >>"$refs"

# Imported targets of our dependencies (written at configure time).
cat "$build/referenced-files.txt" >>"$refs"

# Headers, from the compiler's depfiles.
find "$build" -name '*.o.d' -print0 | xargs -0 -r cat | tr ' \\' '\n\n' | grep '^/' | sort -u |
  sed 's/^/header\t/' >>"$refs"

# Link lines: absolute paths, and -lNAME looked up in the linker's default directories.
libdirs=(/usr/lib/x86_64-linux-gnu /usr/lib /lib/x86_64-linux-gnu /lib)
libdirs=("$(gcc -print-multiarch 2>/dev/null | sed 's|^|/usr/lib/|')" "${libdirs[@]}")
find "$build" -name link.txt -print0 | xargs -0 -r cat | tr ' ' '\n' | sort -u >"$tmp/link"
grep '^/' "$tmp/link" | sed 's/^/link line\t/' >>"$refs" || true
for flag in $(grep '^-l' "$tmp/link" || true); do
  name=${flag#-l}
  found=""
  for d in "${libdirs[@]}"; do
    for f in "$d/lib$name.so" "$d/lib$name.a"; do
      if [[ -z "$found" && -e "$f" ]]; then found=$f; fi
    done
  done
  if [[ -n "$found" ]]; then
    printf 'link line (%s)\t%s\n' "$flag" "$found" >>"$refs"
  else
    printf 'link line (%s)\t%s\n' "$flag" "(not found)" >>"$refs"
  fi
done

# What the compiler driver adds to each link by itself (crt files, libstdc++, the sanitizer
# and libFuzzer runtimes of -fsanitize=...): asked of the driver with -### and the link's flags.
find "$build" -name link.txt -print0 | xargs -0 -r -n1 sh -c \
  'set -- $(cat "$0"); cc=$1; shift; flags=""; for a in "$@"; do case "$a" in -f*|-m*|-static*|-shared|-pie|-no-pie) flags="$flags $a";; esac; done; echo "$cc$flags"' |
  sort -u >"$tmp/drivers"
: >"$tmp/empty.o"
while read -r cc flags; do
  case "$(basename "$cc")" in *ar|*ranlib) continue ;; esac  # static libraries: no link
  # shellcheck disable=SC2086
  { "$cc" $flags -### "$tmp/empty.o" -o "$tmp/a.out" 2>&1 || true; } | tail -1 |
    tr ' ' '\n' | tr -d '"' | { grep '^/' || true; } | { grep -v "^$tmp" || true; } |
    sed "s|^|implicit link input ($(basename "$cc"))\t|"
done <"$tmp/drivers" >>"$refs"

# Shared libraries the built programs load.
for exe in "$build"/bin/*; do
  [[ -x "$exe" && -f "$exe" ]] || continue
  ldd "$exe" 2>/dev/null | awk -v exe="$(basename "$exe")" \
    '$2 == "=>" && $3 ~ /^\// { print "loaded by " exe "\t" $3 } $1 ~ /^\// { print "loaded by " exe "\t" $1 }'
done >>"$refs"

# Tools: what CMake configured, what the tests' commands start with, what this check runs.
for var in CMAKE_CXX_COMPILER CMAKE_MAKE_PROGRAM CMAKE_COMMAND CMAKE_CTEST_COMMAND CMAKE_AR \
           CMAKE_RANLIB CMAKE_LINKER; do
  value=$(sed -n "s/^$var:[A-Z]*=//p" "$build/CMakeCache.txt")
  [[ "$value" == /* ]] && printf 'tool %s\t%s\n' "$var" "$value" >>"$refs"
done
find "$build" -name CTestTestfile.cmake -print0 | xargs -0 -r grep -ho 'add_test([^ ]* "[^"]*"' |
  sed 's/.*"\(.*\)"/\1/' | grep '^/' | sort -u | sed 's/^/test command\t/' >>"$refs" || true
for tool in bash dpkg-query ldd awk sed grep find xargs sort gcc; do
  printf 'tool %s\t%s\n' "$tool" "$(command -v "$tool")" >>"$refs"
done
# What the test scripts run besides: a pseudo-terminal (script) and a Slurm cluster.
for tool in script munged mungekey munge unmunge slurmctld slurmd sbatch squeue sinfo scontrol; do
  path=$(command -v "$tool" || true)
  if [[ -z "$path" ]]; then
    echo "check-deps: FAILED: the tests run $tool, which is not installed" >&2
    exit 1
  fi
  printf 'tool %s\t%s\n' "$tool" "$path" >>"$refs"
done

# The Python modules the tests and the Python example import, as the interpreter that runs
# them finds them.
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
if [[ -n "$python" ]]; then
  for module in numpy pytest matplotlib; do
    path=$("$python" -c "import $module; print($module.__file__)" 2>/dev/null || true)
    if [[ -z "$path" ]]; then
      echo "check-deps: FAILED: the Python tests import $module, which $python cannot" >&2
      exit 1
    fi
    printf 'python module %s\t%s\n' "$module" "$path" >>"$refs"
  done
fi

# Our own files are not packages.
grep -v -P "\t(\Q$root\E|\Q$build\E)/" "$refs" | sort -u >"$tmp/refs.ext" || true

# ---- 2. each file's package ----
# dpkg's file lists, indexed once; with merged /usr a file may be listed under /lib or
# /usr/lib, so both spellings are tried, and then the path with its symbolic links resolved
# (/usr/bin/c++ belongs to no package: it is an alternative for g++-12's binary).
# (One realpath for all of them: a readlink per file was most of this script's time.)
awk -F'\t' '{ print $2 }' "$tmp/refs.ext" | sort -u >"$tmp/files"
xargs -r -d '\n' realpath -m -- <"$tmp/files" | paste "$tmp/files" - >"$tmp/paths"

awk -F'\t' '
  function alt(p) {
    if (p ~ /^\/usr\/(lib|lib64|bin|sbin)\//) return substr(p, 5)
    if (p ~ /^\/(lib|lib64|bin|sbin)\//) return "/usr" p
    return ""
  }
  FNR == 1 { file++ }
  file == 1 { want[$1] = 1; want[$2] = 1; a = alt($1); if (a != "") want[a] = 1
              a = alt($2); if (a != "") want[a] = 1; next }
  file >= 2 {
    if ($0 in want) {
      pkg = FILENAME; sub(/.*\//, "", pkg); sub(/\.list$/, "", pkg); sub(/:.*/, "", pkg)
      owners[$0] = owners[$0] (owners[$0] == "" ? "" : ",") pkg
    }
  }
  END {
    for (p in want) if (p in owners) print p "\t" owners[p]
  }' "$tmp/paths" /var/lib/dpkg/info/*.list >"$tmp/owners"

# ---- 3. the closure of what install-deps.sh installs, plus every system's base ----
mapfile -t named < <("$root/tools/install-deps.sh" --list)
kept=()
for p in "${named[@]}"; do
  drop=0
  for w in "${without[@]}"; do [[ "$p" == "$w" ]] && drop=1; done
  [[ $drop -eq 1 ]] || kept+=("$p")
done
named=("${kept[@]}")
dpkg-query -W -f '${Package}\t${db:Status-Abbrev}\t${Essential}\t${Priority}\t${Provides}\t${Pre-Depends}, ${Depends}\n' \
  >"$tmp/status"
printf '%s\n' "${named[@]}" | grep . >"$tmp/named" || true
awk -F'\t' '
  function strip(s) { gsub(/\([^)]*\)/, "", s); gsub(/:[a-z0-9]+/, "", s); gsub(/[ ]/, "", s); return s }
  FNR == 1 { file++ }
  file == 1 { seed[$1] = 1; next }
  $2 !~ /^ii/ { next }
  {
    installed[$1] = 1; deps[$1] = $6
    if ($3 == "yes" || $4 == "required") seed[$1] = 1
    n = split($5, prov, ",")
    for (i = 1; i <= n; i++) { v = strip(prov[i]); if (v != "") providers[v] = providers[v] " " $1 }
  }
  END {
    for (p in seed) if (p in installed) { queue[++tail] = p; in_closure[p] = 1 }
    for (head = 1; head <= tail; head++) {
      n = split(deps[queue[head]], clauses, ",")
      for (i = 1; i <= n; i++) {
        # "a | b": every installed alternative may be the one a fresh install chose.
        m = split(clauses[i], alts, "|")
        for (j = 1; j <= m; j++) {
          d = strip(alts[j]); if (d == "") continue
          cands = (d in installed) ? d : providers[d]
          k = split(cands, cs, " ")
          for (c = 1; c <= k; c++)
            if (cs[c] != "" && !(cs[c] in in_closure)) { in_closure[cs[c]] = 1; queue[++tail] = cs[c] }
        }
      }
    }
    for (p in in_closure) print p
  }' "$tmp/named" "$tmp/status" | sort >"$tmp/closure"

# ---- 4. verdict ----
awk -F'\t' '
  FNR == 1 { file++ }
  file == 1 { closure[$1] = 1; next }
  file == 2 { resolved[$1] = $2; next }
  file == 3 { owner[$1] = $2; next }
  {
    what = $1; path = $2; real = resolved[path]
    own = owner[path]
    if (own == "" && real != "") own = owner[real]
    if (own == "") {
      for (k = 0; k < 2 && own == ""; k++) {
        p = k == 0 ? path : real
        if (p ~ /^\/usr\/(lib|lib64|bin|sbin)\//) q = substr(p, 5); else q = "/usr" p
        own = owner[q]
      }
    }
    checked++
    if (own == "") { print (system("test -e \"" path "\"") == 0 ? "UNOWNED" : "ABSENT") "\t" what "\t" path; next }
    n = split(own, os, ","); ok = 0
    for (i = 1; i <= n; i++) { used[os[i]] = 1; if (os[i] in closure) ok = 1 }
    if (!ok) print "MISSING\t" what "\t" path "\t" own
  }
  END {
    np = 0; for (p in used) np++
    print "SUMMARY\t" checked "\t" np > "/dev/stderr"
  }' "$tmp/closure" "$tmp/paths" "$tmp/owners" "$tmp/refs.ext" >"$tmp/verdict" 2>"$tmp/summary"

read -r _ checked npkgs <"$tmp/summary"
nnamed=$(grep -c . "$tmp/named" || true)
nclosure=$(grep -c . "$tmp/closure" || true)
printf 'check-deps: %d files used by the build, the tests and their tools, from %d packages;\n' \
  "$checked" "$npkgs"
printf 'check-deps: install-deps.sh names %d packages, whose Depends/Pre-Depends closure with the\n' "$nnamed"
printf 'check-deps: Essential and required packages holds %d' "$nclosure"
[[ ${#without[@]} -gt 0 ]] && printf ' (without %s)' "${without[*]}"
printf '\n'
awk -F'\t' '{ print $1 }' "$tmp/refs.ext" | sed 's/ (.*//; s/^loaded by .*/shared library loaded by a program/; s/^tool .*/tool/; s/^imported target .*/imported target file/; s/^implicit link input.*/implicit link input (compiler driver)/' |
  sort | uniq -c | sed 's/^ */check-deps:   /'

status=0
if grep -q '^MISSING' "$tmp/verdict"; then
  status=1
  echo "check-deps: FAILED: files from packages that tools/install-deps.sh does not install:"
  grep '^MISSING' "$tmp/verdict" | sort -t$'\t' -k4,4 -k3,3 |
    awk -F'\t' '{ printf "check-deps:   %s (%s): %s\n", $3, $2, $4 }'
  echo "check-deps: add the package(s) above to tools/install-deps.sh, or stop using the files."
fi
if grep -q '^UNOWNED' "$tmp/verdict"; then
  status=1
  echo "check-deps: FAILED: files that no Debian package owns (installed by hand?):"
  grep '^UNOWNED' "$tmp/verdict" | sort -u | awk -F'\t' '{ printf "check-deps:   %s (%s)\n", $3, $2 }'
fi
if grep -q '^ABSENT' "$tmp/verdict"; then
  # Debian's Imath config, for one, declares a Python binding that python3-imath would install;
  # CMake checks such files only for packages whose config asks it to, and we use none of them.
  echo "check-deps: note: files that imported targets declare but that do not exist (unused):"
  grep '^ABSENT' "$tmp/verdict" | sort -u | awk -F'\t' '{ printf "check-deps:   %s (%s)\n", $3, $2 }'
fi
[[ $status -eq 0 ]] && echo "check-deps: OK: every package used is installed by tools/install-deps.sh or its dependencies"
exit $status
