#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, from Debian 12's packages (slurm-wlm 22.05, munge), for the
# sweep tests and for trying `workbench sweep --slurm` (docs/sweeps.md). Run as root.
#
#   scripts/slurm-local.sh start    install the packages if missing, write the configuration, start munged,
#                                   slurmctld and slurmd, wait until `sinfo` shows the node idle
#   scripts/slurm-local.sh stop     stop the daemons this script started
#   scripts/slurm-local.sh status   say whether they run, and sinfo
#
# With `--holder NAME` (the tests pass their build folder) start registers NAME as a user of the cluster and
# stop unregisters it, stopping the daemons only when no holder is left: test runs of several build folders
# share one cluster without stopping it under each other. A plain `stop` stops it whatever holds it.
#
# Containers have no systemd and often no writable cgroups: the daemons are started directly, and the
# configuration tracks processes by their parent (proctrack/linuxproc), binds nothing (task/none) and keeps
# no accounting. The node is this machine with its cores and memory as `slurmd -C` reports them.
# The configuration is /etc/slurm/slurm.conf (where every Slurm command looks); one that this script did not
# write is never overwritten. State, logs and pid files: /var/lib/rt-workbench/slurm.
set -euo pipefail

state=/var/lib/rt-workbench/slurm
conf=/etc/slurm/slurm.conf
marker="# written by rt-workbench scripts/slurm-local.sh"
say() { echo "slurm-local: $*"; }
die() {
  echo "slurm-local: error: $*" >&2
  exit 1
}

alive() { # alive PIDFILE: the process named in PIDFILE runs
  [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null
}

install_packages() {
  if command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v sbatch >/dev/null &&
    command -v munged >/dev/null; then
    return
  fi
  [ "$(id -u)" -eq 0 ] || die "the Slurm packages are missing and installing them needs root: run this as root"
  say "installing slurm-wlm and munge (apt)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends slurm-wlm slurm-client munge
}

write_config() {
  if [ -f "$conf" ] && ! grep -qF "$marker" "$conf"; then
    die "$conf exists and was not written by this script: not touching a real cluster's configuration"
  fi
  mkdir -p /etc/slurm "$state"/ctld "$state"/d "$state"/log "$state"/run
  # The node as slurmd sees it (CPUs, sockets, cores, threads, memory): a node configured with more than it
  # finds is drained.
  local node
  node=$(slurmd -C | head -n1)
  case "$node" in NodeName=*) ;; *) die "slurmd -C gave no node line: $node" ;; esac
  local name
  name=$(echo "$node" | sed 's/^NodeName=\([^ ]*\).*/\1/')
  cat >"$conf.tmp" <<EOF
$marker
ClusterName=rtwb
SlurmctldHost=$name(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/d
SlurmctldPidFile=$state/run/slurmctld.pid
SlurmdPidFile=$state/run/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
# No cgroups: containers often lack them.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
# Start queued jobs at the next second rather than after 3 (short tasks: the node idles less).
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MaxArraySize=10001
MaxJobCount=100000
MinJobAge=600
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=60
InactiveLimit=0
$node State=UNKNOWN NodeAddr=127.0.0.1
PartitionName=local Nodes=$name Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
  config_changed=0
  if ! cmp -s "$conf.tmp" "$conf"; then config_changed=1; fi
  mv "$conf.tmp" "$conf"
  echo "$name" >"$state/node"
}

start_munge() {
  if [ ! -s /etc/munge/munge.key ]; then
    mkdir -p /etc/munge
    if command -v mungekey >/dev/null; then mungekey --create --keyfile=/etc/munge/munge.key; else
      dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
    fi
    chown munge:munge /etc/munge/munge.key
    chmod 400 /etc/munge/munge.key
  fi
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  if alive /run/munge/munged.pid; then return; fi
  runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/munged.pid
  for _ in $(seq 50); do
    if munge -n </dev/null | unmunge >/dev/null 2>&1; then return; fi
    sleep 0.2
  done
  die "munged does not answer (munge -n | unmunge fails); see /var/log/munge/munged.log"
}

start() {
  install_packages
  write_config
  start_munge
  if ! alive "$state/run/slurmctld.pid"; then
    /usr/sbin/slurmctld || die "slurmctld did not start; see $state/log/slurmctld.log"
  fi
  if ! alive "$state/run/slurmd.pid"; then
    /usr/sbin/slurmd -N "$(cat "$state/node")" || die "slurmd did not start; see $state/log/slurmd.log"
  elif [ "$config_changed" = 1 ]; then
    scontrol reconfigure || die "scontrol reconfigure failed on the new $conf"
  fi
  local node t=0
  node=$(cat "$state/node")
  while :; do
    local st
    st=$(sinfo -h -n "$node" -o '%T' 2>/dev/null || true)
    case "$st" in
    idle* | mixed* | allocated*)
      say "node $node is $st ($(sinfo -h -n "$node" -o '%c CPUs, %m MB'))"
      return
      ;;
    drain* | down* | fail*)
      # A node left down by an earlier run comes back once it answers.
      scontrol update nodename="$node" state=resume >/dev/null 2>&1 || true
      ;;
    esac
    t=$((t + 1))
    if [ "$t" -ge 120 ]; then
      echo "slurm-local: error: node $node is '${st:-not known}' after 60 s; sinfo -R:" >&2
      sinfo -R >&2 || true
      tail -n 20 "$state/log/slurmctld.log" "$state/log/slurmd.log" >&2 || true
      exit 1
    fi
    sleep 0.5
  done
}

stop_one() { # stop_one NAME PIDFILE
  if ! alive "$2"; then return; fi
  local pid
  pid=$(cat "$2")
  kill "$pid"
  for _ in $(seq 100); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  die "$1 (pid $pid) did not stop within 10 s"
}

stop() {
  stop_one slurmd "$state/run/slurmd.pid"
  stop_one slurmctld "$state/run/slurmctld.pid"
  stop_one munged /run/munge/munged.pid
  say "stopped"
}

status() {
  for d in slurmctld slurmd; do
    if alive "$state/run/$d.pid"; then say "$d runs (pid $(cat "$state/run/$d.pid"))"; else say "$d is not running"; fi
  done
  if alive /run/munge/munged.pid; then say "munged runs"; else say "munged is not running"; fi
  sinfo 2>/dev/null || true
}

holder=""
if [ "${2:-}" = "--holder" ] && [ -n "${3:-}" ]; then holder=$(echo "$3" | sha256sum | cut -c1-16); fi
holders="$state/holders"

case "${1:-}" in
start)
  # The holder is registered before the start: a concurrent `stop --holder` of another build sees it.
  if [ -n "$holder" ]; then mkdir -p "$holders" && echo "$3" >"$holders/$holder"; fi
  start
  ;;
stop)
  if [ -n "$holder" ]; then
    rm -f "$holders/$holder"
    if [ -n "$(ls -A "$holders" 2>/dev/null)" ]; then
      say "still held by $(cat "$holders"/* | tr '\n' ' '): left running"
      exit 0
    fi
  fi
  stop
  ;;
status) status ;;
*)
  echo "usage: $0 start|stop|status [--holder NAME]" >&2
  exit 2
  ;;
esac
