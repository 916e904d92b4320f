#!/usr/bin/env bash
# Packs the benchmark suite for a bare Linux x86-64 machine that has none of our packages (the
# 16-core machine some sessions are lent for the 1-16-thread scaling):
#
#   tools/device-bundle.sh [BUILD_DIR] [DEST]      (defaults: build, .device)
#
# DEST/bundle.tar.xz (about 14 MiB) holds bin/ (wavetrace_bench, kernel_bench), lib/ (every
# shared library they load, but the C library's, which any glibc >= Debian 12's serves) and
# run.sh, which runs a program with lib/ first on the library path. There:
#   mkdir -p /tmp/wt && tar -xJf .device/bundle.tar.xz -C /tmp/wt
#   /tmp/wt/run.sh wavetrace_bench --sections scaling --scenes scenes ...
#
# One substitution, because the transfer is limited to 64 MiB: OpenImageIO drags in about 250
# libraries (ffmpeg, GDAL, OpenVDB, ...; 400 MiB, 100 MiB compressed), and the benchmarks
# never read or write an image. lib/ gets a stand-in libOpenImageIO that defines the few
# symbols the programs import, each one stopping the program with a message if it is ever
# called; the rendering code that is measured is the same binary's, unchanged.
set -euo pipefail
build=${1:-build}
dest=${2:-.device}
programs=(wavetrace_bench kernel_bench)

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
out=$dest
dest=$stage
mkdir -p "$dest/bin" "$dest/lib"
for p in "${programs[@]}"; do cp "$build/bin/$p" "$dest/bin/"; done

# The stand-in: one function per imported OpenImageIO symbol (mangled C++ names are valid C
# identifiers), in a library with the real one's soname.
oiio=libOpenImageIO.so.2.4
{
    echo '#include <stdio.h>'
    echo '#include <stdlib.h>'
    echo 'static void missing(const char* s) {'
    echo '    fprintf(stderr, "device bundle: OpenImageIO is not carried (%s called)\n", s);'
    echo '    abort();'
    echo '}'
    for p in "${programs[@]}"; do nm -D --undefined-only "$dest/bin/$p"; done |
        awk '$2 ~ /OpenImageIO_v/ && $2 !~ /OpenImageIO_v[0-9_]+Filesystem/ {print $2}' | sort -u |
        while read -r s; do
            case $s in *@*) echo "symbol with a version: $s" >&2; exit 1 ;; esac
            echo "void $s(void) { missing(\"$s\"); }"
        done
} >"$dest/oiio-standin.c"
cc -shared -fPIC -O1 -Wl,-soname,$oiio -o "$dest/lib/$oiio" "$dest/oiio-standin.c"
rm "$dest/oiio-standin.c"

# Everything else the programs load, resolved with the stand-in in place of the real one.
for p in "${programs[@]}"; do LD_LIBRARY_PATH="$dest/lib" ldd "$dest/bin/$p"; done |
    awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
    grep -vE '/(libc|libm|libpthread|libdl|librt|ld-linux-x86-64)\.so' |
    grep -v "^$(cd "$dest/lib" && pwd)/" |
    while read -r lib; do cp -L "$lib" "$dest/lib/"; done

cat >"$dest/run.sh" <<'RUN'
#!/usr/bin/env bash
# Runs one of bin/'s programs with the carried libraries first on the library path.
here=$(cd "$(dirname "$0")" && pwd)
prog=$1
shift
LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/bin/$prog" "$@"
RUN
chmod +x "$dest/run.sh"

# Every library must resolve inside the bundle or be the C library's.
for p in "${programs[@]}"; do
    if LD_LIBRARY_PATH="$dest/lib" ldd "$dest/bin/$p" | grep -q 'not found'; then
        echo "$p: unresolved libraries" >&2
        exit 1
    fi
done
mkdir -p "$out"
tar -C "$dest" -cf - . | xz -6 -T0 >"$out/bundle.tar.xz"
du -h "$out/bundle.tar.xz"
