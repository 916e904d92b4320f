#!/bin/bash
# Renders every shipped scene small with both engines (and a normal AOV), veach-mis and
# cornell-smoke with every strategy, and prints each image's sha256: run it with the CLI
# before and after a change that must not change images, and diff the two outputs.
# usage: tools/image-hashes.sh [WAVETRACE_BINARY] > hashes.txt
set -euo pipefail
cli=${1:-build/bin/wavetrace}
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
render() {  # name, then the render's arguments
  local name=$1
  shift
  "$cli" render "$@" --width 40 --height 40 -o "$out/$name.pfm" > /dev/null 2> "$out/err" ||
    { cat "$out/err" >&2; exit 1; }
}
for scene in "$root"/scenes/*.json; do
  n=$(basename "$scene" .json)
  for engine in wavefront megakernel; do render "$n.$engine" "$scene" --spp 3 --engine "$engine"; done
  render "$n.normal" "$scene" --spp 2 --aov normal
done
for strategy in bsdf light mixture nee; do
  render "veach-mis.$strategy" "$root/scenes/veach-mis.json" --spp 3 --strategy "$strategy"
  render "cornell-smoke.$strategy" "$root/scenes/cornell-smoke.json" --spp 3 --strategy "$strategy" \
    --engine megakernel
done
(cd "$out" && sha256sum -- *.pfm)
