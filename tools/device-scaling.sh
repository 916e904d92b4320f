#!/usr/bin/env bash
# The 1-16-thread run on a lent device machine (docs/benchmarks.md, "Thread scaling"), from the
# bundle that tools/device-bundle.sh packs into .device/:
#
#   tools/device-bundle.sh build .device
#   (on the device, from the repository root, with .device carried)  tools/device-scaling.sh
#
# It writes to $OUT: machine.txt (CPU, cores, SMT siblings, caches), scaling/ and engines/
# (the suite's CSV and JSON) and their logs. `everything` is left out: its earth texture needs
# OpenImageIO, which the bundle does not carry. The scaling section renders three engines per
# count (the megakernel, the wavefront's resident and stage schedules) plus the renders alone;
# at three repetitions it takes about 85 s a scene on that machine, the engines section ~90 s:
# give the run a timeout_s of about 570 (a start took ~40 s of the device time), or set
# SCALING_SECONDS / ENGINES_SECONDS / SCALING_REPETITIONS.
set -uo pipefail
out=${OUT:?OUT must name the folder the results go to}
mkdir -p /tmp/wt && tar -xJf .device/bundle.tar.xz -C /tmp/wt
{
    nproc
    lscpu
    echo "thread siblings of cpu0: $(cat /sys/devices/system/cpu/cpu0/topology/thread_siblings_list)"
    echo "core ids: $(cat /sys/devices/system/cpu/cpu*/topology/core_id | sort -n | uniq -c | tr '\n' ' ')"
    grep -m1 MHz /proc/cpuinfo
    free -g
} >"$out/machine.txt" 2>&1
scenes=(--scene cornell --scene bunny --scene dragon --scene veach-mis)
timeout "${SCALING_SECONDS:-400}" /tmp/wt/run.sh wavetrace_bench --sections scaling \
    --max-threads 16 --repetitions "${SCALING_REPETITIONS:-3}" --scenes scenes "${scenes[@]}" \
    --out "$out/scaling" 2>&1 |
    tee "$out/scaling.log"
timeout "${ENGINES_SECONDS:-120}" /tmp/wt/run.sh wavetrace_bench --sections engines \
    --repetitions 3 --scenes scenes "${scenes[@]}" --out "$out/engines" 2>&1 |
    tee "$out/engines.log"
