#!/bin/bash
# A render against another renderer's reference, as a user would check it: `wavetrace render
# --variance`, then `wavetrace compare` with both variances (its pass rule: docs/validation.md).
# REF_VARIANCE "-": the reference counts as converged (its mean's variance is negligible).
# usage: reference_test.sh WAVETRACE SCENE.json REF.exr REF_VARIANCE.exr SPP ENGINE [SEED]
set -u
wavetrace=$1 scene=$2 ref=$3 ref_var=$4 spp=$5 engine=$6 seed=${7:-1}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$wavetrace" render "$scene" --spp "$spp" --engine "$engine" --seed "$seed" \
  -o "$out/ours.exr" --variance "$out/ours-var.exr" || exit 1
ref_var_args=(--ref-var "$ref_var")
[ "$ref_var" = - ] && ref_var_args=()
"$wavetrace" compare "$out/ours.exr" "$ref" --ours-var "$out/ours-var.exr" "${ref_var_args[@]}"
