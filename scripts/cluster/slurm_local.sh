#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for trying the sbatch recipes here and for
# their test: munged, slurmctld and slurmd on localhost, everything (key, sockets, state,
# logs, slurm.conf) in one folder. Needs root (SlurmUser=root) and Debian's slurm-wlm and
# munge (scripts/setup.sh installs them).
#
# usage: scripts/cluster/slurm_local.sh start DIR   then: export SLURM_CONF=DIR/slurm.conf
#        scripts/cluster/slurm_local.sh stop DIR    (stops the three daemons it started)
set -euo pipefail
action=${1:-} dir=${2:-}
if [ -z "$action" ] || [ -z "$dir" ]; then
  sed -n '2,9p' "$0" >&2
  exit 2
fi

stop() {
  for daemon in slurmd slurmctld munged; do
    if [ -f "$dir/$daemon.pid" ]; then
      kill "$(cat "$dir/$daemon.pid")" 2>/dev/null || true
      rm -f "$dir/$daemon.pid"
    fi
  done
}

wait_for() {  # wait_for SECONDS COMMAND...: until the command succeeds, or fail
  local limit=$1
  shift
  for _ in $(seq "$limit"); do
    if "$@" >/dev/null 2>&1; then return 0; fi
    sleep 1
  done
  echo "slurm_local.sh: gave up waiting for: $*" >&2
  return 1
}

write_conf() {
  local port=$((20000 + RANDOM % 20000))
  cat > "$dir/slurm.conf" <<CONF
ClusterName=photovrlocal
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "slurm_local.sh: needs root (SlurmUser=root)" >&2; exit 77; }
  for tool in munged mungekey slurmctld slurmd sinfo; do
    command -v "$tool" >/dev/null || { echo "slurm_local.sh: $tool missing (scripts/setup.sh installs slurm-wlm and munge)" >&2; exit 77; }
  done
  mkdir -p "$dir/state" "$dir/spool"
  rm -f "$dir/munge.key"
  mungekey --create --keyfile "$dir/munge.key"
  chmod 600 "$dir/munge.key"
  munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge.seed"
  write_conf
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF" -N localhost
  wait_for 30 sh -c "sinfo -h -o %T | grep -qx idle"
}

case $action in
  start) start ;;
  stop) stop ;;
  *) sed -n '2,9p' "$0" >&2; exit 2 ;;
esac
