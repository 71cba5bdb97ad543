#!/usr/bin/env bash
# Starts (or stops) a single-node Slurm cluster on this machine, for tests
# and for trying deploy/slurm/ without a real cluster. Needs root and the
# Debian packages slurm-wlm and munge (scripts/setup.sh installs them).
#
#   deploy/slurm/local-cluster.sh start DIR   # prints: export SLURM_CONF=...
#   deploy/slurm/local-cluster.sh stop DIR
#
# Everything lives in DIR (configuration, state, logs, pid files); the
# cluster has one node (this host, all its cores) in partition "animat",
# on non-default ports. munged is started if it is not running (with a
# key made once in /etc/munge/munge.key) and left running.
set -euo pipefail

command=${1:?start or stop}
dir=${2:?a directory for the cluster}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
conf="$dir/slurm.conf"

start_munge() {
  if pgrep -x munged >/dev/null; then return; fi
  if [ ! -s /etc/munge/munge.key ]; then
    install -d -o munge -g munge -m 700 /etc/munge
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  chown munge:munge /etc/munge/munge.key
  chmod 400 /etc/munge/munge.key
  install -d -o munge -g munge -m 755 /run/munge
  install -d -o munge -g munge -m 700 /var/lib/munge /var/log/munge
  runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do
    [ -S /run/munge/munge.socket.2 ] && return
    sleep 0.1
  done
  echo "local-cluster: munged did not start" >&2
  exit 1
}

write_conf() {
  local host cpus
  host=$(hostname)
  cpus=$(nproc)
  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  cat > "$conf" <<CONF
ClusterName=animat-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
KillWait=30
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=animat Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

stop_daemon() {
  local pidfile=$1
  if [ -s "$pidfile" ]; then
    local pid
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 100); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$pidfile"
  fi
}

case "$command" in
  start)
    start_munge
    write_conf
    export SLURM_CONF="$conf"
    /usr/sbin/slurmctld -f "$conf"
    /usr/sbin/slurmd -f "$conf"
    # Ready when the node takes jobs.
    for _ in $(seq 300); do
      state=$(sinfo -h -N -o %t 2>/dev/null | head -1 || true)
      case "$state" in
        idle|mix|alloc)
          # Our daemons, not another cluster's on the same ports.
          for daemon in slurmctld slurmd; do
            if ! kill -0 "$(cat "$dir/$daemon.pid" 2>/dev/null)" 2>/dev/null; then
              echo "local-cluster: $daemon is not running (another cluster" \
                "on ports 16817-16818?); logs in $dir/log" >&2
              exit 1
            fi
          done
          echo "export SLURM_CONF=$conf"
          exit 0
          ;;
      esac
      sleep 0.2
    done
    echo "local-cluster: the node did not come up; logs in $dir/log" >&2
    exit 1
    ;;
  stop)
    stop_daemon "$dir/slurmd.pid"
    stop_daemon "$dir/slurmctld.pid"
    ;;
  *)
    echo "usage: $0 start|stop DIR" >&2
    exit 2
    ;;
esac
