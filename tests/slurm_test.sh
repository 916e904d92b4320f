#!/bin/bash
# The `slurm` test: a one-node Slurm cluster from Debian's packages (munged, slurmctld, slurmd
# in a private folder), tools/slurm/submit.sh renders a scene as a 4-task job array plus the
# dependent merge, and the merged image must equal a single render of all the samples (within
# double rounding: wavetrace compare with bounds of 1e-6). The cluster is shut down however the
# test ends. See ../shared/docs/slurm-notes.md for the settings; runs as root (slurmd must).
# usage: slurm_test.sh WAVETRACE SOURCE_DIR
set -euo pipefail
wavetrace=$1 src=$2
if [[ $(id -u) -ne 0 ]]; then
  echo "slurm test: needs root (slurmd runs jobs as their users); skipped" >&2
  exit 77
fi
for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$tool" > /dev/null || { echo "slurm test: $tool missing (tools/install-deps.sh installs slurm-wlm munge)" >&2; exit 1; }
done

t=$(mktemp -d /tmp/wavetrace-slurm.XXXXXX)
chmod 755 "$t"
pids=() munged=""
cleanup() {
  SLURM_CONF=$t/slurm.conf scontrol shutdown > /dev/null 2>&1 || true
  for _ in $(seq 40); do
    alive=0
    for p in "${pids[@]}"; do kill -0 "$p" 2> /dev/null && alive=1; done
    [[ $alive -eq 0 ]] && break
    sleep 0.25
  done
  for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null || true; done
  if [[ -n $munged ]]; then
    kill "$munged" 2> /dev/null || true
    wait "$munged" 2> /dev/null || true
  fi
  rm -rf "$t"
}
trap cleanup EXIT

# --- munge: our own daemon and key ---
mkdir -p "$t/munge" && chmod 755 "$t/munge"
mungekey -c -k "$t/munge.key" > /dev/null 2>&1
chmod 600 "$t/munge.key"
munged -F --socket="$t/munge/sock" --key-file="$t/munge.key" --pid-file="$t/munged.pid" \
  --log-file="$t/munged.log" --seed-file="$t/munged.seed" --force &
munged=$!
for _ in $(seq 40); do [[ -S $t/munge/sock ]] && break; sleep 0.1; done
munge -n -S "$t/munge/sock" | unmunge -S "$t/munge/sock" > /dev/null

# --- slurm: one node, this machine's CPUs and memory, private ports and paths ---
host=$(hostname -s)
cpus=$(nproc)
mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
port=$(( 20000 + $$ % 20000 ))
mkdir -p "$t/state" "$t/spool" "$t/log"
cat > "$t/slurm.conf" <<CONF
ClusterName=wavetrace-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$t/munge/sock
StateSaveLocation=$t/state
SlurmdSpoolDir=$t/spool
SlurmctldPidFile=$t/slurmctld.pid
SlurmdPidFile=$t/slurmd.pid
SlurmctldLogFile=$t/log/slurmctld.log
SlurmdLogFile=$t/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
SchedulerParameters=batch_sched_delay=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
echo "CgroupPlugin=cgroup/v1" > "$t/cgroup.conf"
export SLURM_CONF=$t/slurm.conf
slurmctld -D -f "$SLURM_CONF" > "$t/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" > "$t/log/slurmd.out" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 120); do
  state=$(sinfo -h -n "$host" -o %t 2> /dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.25
done
if [[ $state != idle ]]; then
  echo "slurm test: the node did not come up (state '$state')" >&2
  tail -n 20 "$t"/log/* >&2
  exit 1
fi

# --- the split render and its merge, then the same render in one piece ---
scene=$src/scenes/cornell.json
# zsobol: its layout (--sampler-spp, which submit.sh passes) must agree across the parts.
args="--width 64 --height 48 --seed 5 --sampler zsobol"
merge_job=$("$src/tools/slurm/submit.sh" --parts 4 --spp-per-part 4 --wavetrace "$wavetrace" \
  "$t/out" "$scene" $args)
for _ in $(seq 480); do
  [[ -z $(squeue -h 2> /dev/null) ]] && break
  sleep 0.25
done
if [[ -n $(squeue -h) ]]; then
  echo "slurm test: jobs still queued after 2 minutes:" >&2
  squeue >&2
  exit 1
fi
if [[ ! -f $t/out/image.exr ]]; then
  echo "slurm test: merge job $merge_job wrote no image; the jobs' logs:" >&2
  cat "$t"/out/slurm-*.log >&2
  exit 1
fi
grep -h "merged 4 films" "$t"/out/slurm-merge-*.log
"$wavetrace" render "$scene" $args --spp 16 -o "$t/single.exr" 2> /dev/null > /dev/null
"$wavetrace" compare "$t/out/image.exr" "$t/single.exr" --max-mean-diff 1e-6 --max-rel-mse 1e-12
