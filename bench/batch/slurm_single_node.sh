#!/usr/bin/env bash
# Runs the Slurm recipe (cluster/slurm/) on a single-node Slurm started here: Debian's slurm-wlm
# and munge, a slurm.conf for this machine in a temporary folder, slurmctld and slurmd as root.
# Submits a generated batch of COUNT parts as an array of SHARDS tasks, waits for it, and checks
# that the output equals an unsharded `flatcut batch` of the same manifest, byte for byte. When
# STOCK is given, the fan-in nest job runs after the array too.
#
#   sudo bench/batch/slurm_single_node.sh [COUNT=24] [SHARDS=3] [STOCK="--sheet 3000x1500"]
#
# Needs: apt-get install slurm-wlm munge. Stops the daemons it started at the end.
set -euo pipefail
count=${1:-24}
shards=${2:-3}
stock=${3:-}
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${FLATCUT:-$here/target/release/flatcut}
work=$(mktemp -d /tmp/flatcut-slurm.XXXXXX)
host=$(hostname -s)
cpus=$(nproc)
memory=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)

if [ ! -s /etc/munge/munge.key ]; then
    mungekey --create --keyfile=/etc/munge/munge.key
    chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
fi
mkdir -p /run/munge && chown munge:munge /run/munge
pgrep -x munged > /dev/null || runuser -u munge -- munged

mkdir -p "$work/state" "$work/spool" "$work/log"
cat > "$work/slurm.conf" <<CONF
ClusterName=flatcut
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=main Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld
slurmd
stop_daemons() {
    scancel --user=root 2> /dev/null || true
    kill "$(cat "$work/slurmd.pid")" "$(cat "$work/slurmctld.pid")" 2> /dev/null || true
}
trap stop_daemons EXIT
for _ in $(seq 50); do
    sinfo -h -o %T 2> /dev/null | grep -q idle && break
    sleep 0.2
done
sinfo

"$here/bench/batch/make_batch.sh" "$work/batch" "$count" > /dev/null
manifest=$work/batch/parts.csv
started=$(date +%s)
export FLATCUT=$bin
if [ -n "$stock" ]; then
    read -r array nest < <("$here/cluster/slurm/submit.sh" "$manifest" "$work/out" "$shards" "$stock")
else
    array=$(sbatch --parsable --array="1-$shards" --chdir="$work" \
        --export="ALL,MANIFEST=$manifest,OUT=$work/out" "$here/cluster/slurm/batch.sbatch")
    nest=
fi
echo "submitted array $array ${nest:+and nest $nest}"
while squeue -h | grep -q .; do sleep 1; done
echo "Slurm jobs done in $(($(date +%s) - started)) s"
sacct > /dev/null 2>&1 || true
grep -h "part(s):" "$work"/flatcut-batch-*.log "$here"/flatcut-batch-*.log 2> /dev/null || true

"$bin" batch --manifest "$manifest" -o "$work/unsharded" 2> /dev/null || true
if [ -n "$nest" ]; then
    mv "$work/out/nest" "$work/nest"
fi
if diff -r "$work/unsharded" "$work/out" > "$work/diff.log"; then
    echo "the $shards array tasks' output equals the unsharded batch, byte for byte ($count parts)"
else
    echo "the array's output differs from the unsharded batch:"; head "$work/diff.log"; exit 1
fi
rm -f "$here"/flatcut-batch-*.log "$here"/flatcut-nest-*.log
echo "work folder: $work"
