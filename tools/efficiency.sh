#!/usr/bin/env bash
# Efficiency of renderer builds at equal samples or equal time: 1 / (relative MSE x time)
# against a converged reference, the measure path termination is chosen by (docs/sampling.md).
#
#   tools/efficiency.sh SCENE REFERENCE SPP|SECONDSs SEEDS WAVETRACE...
#
# Renders SCENE with each WAVETRACE binary at SPP samples, seeds 1..SEEDS, two threads, the
# binaries interleaved seed by seed; prints per binary the median samples and render time, the
# mean relative MSE (`wavetrace compare`'s) and their efficiency. A budget such as `25s` instead
# of SPP renders for equal time (`--time-limit 25`: whole passes until the budget is spent),
# which is what a user waits for where the error does not fall as 1/spp (the Sobol sampler's
# falls faster). A WAVETRACE may carry render options after commas
# (`build/bin/wavetrace,--sampler,independent`) to compare settings of one build.
# SIZE=N in the environment renders N x N (the reference must be that size). A reference of our
# own: `wavetrace render SCENE --spp 4096 --sampler sobol --seed 99 -o ref.exr`.
set -euo pipefail
[[ $# -ge 5 ]] || { echo "usage: $0 SCENE REFERENCE SPP|SECONDSs SEEDS WAVETRACE..." >&2; exit 2; }
scene=$1 ref=$2 spp=$3 seeds=$4
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size=()
[[ -n "${SIZE:-}" ]] && size=(--width "$SIZE" --height "$SIZE")
budget=(--spp "$spp")
[[ $spp == *s ]] && budget=(--time-limit "${spp%s}" --spp 1000000)
for seed in $(seq 1 "$seeds"); do
  for i in $(seq 1 $#); do
    IFS=, read -r -a run <<<"${!i}"
    bin=${run[0]}
    # The summary line: "... 512x512 16 spp[ of N requested (time limit reached)]: 1.72 s, ...".
    read -r n t < <("$bin" render "$scene" "${size[@]}" "${run[@]:1}" "${budget[@]}" --seed "$seed" \
          --threads 2 -o "$work/out.exr" 2>&1 |
          sed -n 's/.* \([0-9]*\) spp[^:]*: \([0-9.]*\) s, .*/\1 \2/p')
    # compare exits 1 when the images differ, as these do: only its figures are wanted.
    e=$({ "$bin" compare "$work/out.exr" "$ref" 2>&1 || true; } |
          sed -n 's/^rel\. MSE *\([^ ]*\).*/\1/p' | head -1)
    echo "$i $t $e $n" >>"$work/runs"
  done
done
for i in $(seq 1 $#); do
  python3 - "$work/runs" "$i" "${!i}" <<'PY'
import statistics, sys
runs = [line.split() for line in open(sys.argv[1]) if line.split()[0] == sys.argv[2]]
t = statistics.median(float(r[1]) for r in runs)
e = statistics.mean(float(r[2]) for r in runs)
n = statistics.median(int(r[3]) for r in runs)
print(f"{sys.argv[3]}: {n:g} spp, time {t:.3f} s, rel. MSE {e:.4e}, efficiency {1 / (t * e):.1f}")
PY
done
