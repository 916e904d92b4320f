#!/usr/bin/env bash
# Remakes the figures of docs/sampling.md: each strategy on the Cornell box at 8 and 256 spp,
# and each strategy on Veach's MIS scene at 64 spp. Run from the repository root after
# `make build`; writes docs/images/*.jpg and prints one summary line per render.
set -euo pipefail
bin=build/bin/wavetrace
out=docs/images
mkdir -p "$out"
for strategy in bsdf light mixture nee mis; do
  for spp in 8 256; do
    "$bin" render scenes/cornell.json --strategy "$strategy" --spp "$spp" --width 256 --height 256 \
      --seed 1 -o "$out/cornell-$strategy-$spp.jpg" > /dev/null
  done
  "$bin" render scenes/veach-mis.json --strategy "$strategy" --spp 64 --width 384 --height 288 \
    --seed 1 -o "$out/veach-mis-$strategy-64.jpg" > /dev/null
done
