#!/bin/bash
# Submits a wavetrace render split into PARTS sample ranges as a Slurm job array, and its
# merge as a job that runs when every part has succeeded (docs/distributed.md). OUT must be on
# storage every node sees. Prints the merge job's id.
#   tools/slurm/submit.sh [--parts K] [--spp-per-part N] [--first-sample S] [--cpus C]
#                         [--sampler-spp T] [--wavetrace BIN] [--asset-root DIR]
#                         [--sbatch-args "..."] OUT SCENE.json [render options...]
# Part k renders samples S + [kN, (k + 1)N); S (default 0) adds samples to an earlier split.
# T (default S + KN, at most 2^20) is the count the zsobol sampler lays its sequence out for:
# a later split that adds samples to a zsobol render gives the first split's.
# Every file the scene reads must lie inside the asset root: the scene's folder unless
# --asset-root names another ("" for none).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
parts=4 spp=64 first=0 cpus=1 sbatch_args="" wavetrace=$(command -v wavetrace || true) root=-
sampler_spp=""
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --parts) parts=$2; shift 2 ;;
    --spp-per-part) spp=$2; shift 2 ;;
    --first-sample) first=$2; shift 2 ;;
    --sampler-spp) sampler_spp=$2; shift 2 ;;
    --cpus) cpus=$2; shift 2 ;;
    --wavetrace) wavetrace=$2; shift 2 ;;
    --asset-root) root=$2; shift 2 ;;
    --sbatch-args) sbatch_args=$2; shift 2 ;;
    *) echo "submit.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [[ $# -lt 2 || -z $wavetrace ]]; then
  echo "usage: $0 [--parts K] [--spp-per-part N] [--cpus C] [--wavetrace BIN] OUT SCENE.json [render options...]" >&2
  exit 2
fi
out=$(realpath -m "$1") scene=$(realpath "$2")
shift 2
if [[ $root == - ]]; then root=$(dirname "$scene"); elif [[ -n $root ]]; then root=$(realpath "$root"); fi
mkdir -p "$out"
if [[ -z $sampler_spp ]]; then
  sampler_spp=$((first + parts * spp))
  ((sampler_spp > 1048576)) && sampler_spp=1048576
fi
export WAVETRACE=$(realpath "$wavetrace") SCENE=$scene OUT=$out SPP_PER_PART=$spp FIRST_SAMPLE=$first ASSET_ROOT=$root RENDER_ARGS="$*"
export SAMPLER_SPP=$sampler_spp
# shellcheck disable=SC2086  # sbatch_args is a list of options
# Each part's film is named by its first sample, so splits added later never collide.
array=$(sbatch --parsable --export=ALL --array=0-$((parts - 1)) --cpus-per-task="$cpus" \
  --output="$out/slurm-%A_%a.log" $sbatch_args "$here/render-part.sbatch")
array=${array%%;*}
# shellcheck disable=SC2086
sbatch --parsable --export=ALL --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
  --output="$out/slurm-merge-%j.log" $sbatch_args "$here/merge.sbatch"
