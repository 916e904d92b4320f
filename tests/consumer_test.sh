#!/bin/bash
# Installs this build into a temporary prefix, then configures, builds and runs
# tests/consumer against it with find_package(wavetrace CONFIG REQUIRED), as a user would,
# and imports the Python package from it.
# usage: consumer_test.sh BUILD_DIR SOURCE_DIR CMAKE [PYTHON]
set -euo pipefail
build=$1 src=$2 cmake=$3 python=${4:-}
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
"$cmake" --install "$build" --prefix "$t/prefix" > /dev/null
"$cmake" -S "$src/tests/consumer" -B "$t/build" -DCMAKE_PREFIX_PATH="$t/prefix" \
  -DCMAKE_BUILD_TYPE=Release --log-level=WARNING > /dev/null
"$cmake" --build "$t/build" > /dev/null
"$t/build/consumer"
# The Python package, when the build has it: importable from the prefix alone.
site=$(find "$t/prefix" -path '*/dist-packages/wavetrace/__init__.py' -print -quit)
if [[ -n "$site" && -n "$python" ]]; then
  site=$(dirname "$(dirname "$site")")
  (cd "$t" && PYTHONPATH="$site" "$python" -c \
    "import wavetrace as wt; s = wt.Scene(); print(wt.__file__.startswith('$site'), wt.__version__)" |
    grep -q '^True ')
fi
