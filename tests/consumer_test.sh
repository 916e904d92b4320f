#!/bin/bash
# Installs this build into a temporary prefix, then configures, builds and runs
# tests/consumer against it with find_package(wavetrace CONFIG REQUIRED), as a user would.
# usage: consumer_test.sh BUILD_DIR SOURCE_DIR CMAKE CTEST_BUILD_TYPE
set -euo pipefail
build=$1 src=$2 cmake=$3
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
"$cmake" --install "$build" --prefix "$t/prefix" > /dev/null
"$cmake" -S "$src/tests/consumer" -B "$t/build" -DCMAKE_PREFIX_PATH="$t/prefix" \
  -DCMAKE_BUILD_TYPE=Release --log-level=WARNING > /dev/null
"$cmake" --build "$t/build" > /dev/null
"$t/build/consumer"
