#!/usr/bin/env bash
# A private single-node Slurm cluster on this machine, for testing the batch scripts in
# experiments/slurm/ against a real scheduler (Debian's slurm-wlm and munge; run as root).
#   scripts/slurm-local.sh start DIR   start munged, slurmctld and slurmd with all state in DIR
#   scripts/slurm-local.sh stop DIR    cancel the cluster's jobs, stop the daemons started in DIR
# `start` writes DIR/slurm.conf and DIR/env.sh (source it: SLURM_CONF for sbatch, squeue, ...)
# and returns once the node accepts jobs (or fails within 60 s, printing the daemons' logs).
# Nothing outside DIR is read or written but the packages' programs: a fresh munge key, its own
# munged socket, free TCP ports on 127.0.0.1, one node "localhost" with this machine's CPUs and
# memory (`slurmd -C`), one partition. No cgroups (the machine may be a container): processes are
# tracked by /proc (proctrack/linuxproc), tasks are not bound (task/none), no accounting.
set -euo pipefail

usage() {
  echo "usage: scripts/slurm-local.sh start|stop DIR" >&2
  exit 2
}
[ $# -eq 2 ] || usage
action=$1
dir=$(realpath -m "$2")

# Cancels the jobs still queued or running on the cluster in DIR (their processes would outlive
# slurmd), then stops its daemons, each by the PID it wrote.
stop() {
  local name pid
  if [ -f "$dir/run/slurmctld.pid" ] && [ -f "$dir/slurm.conf" ]; then
    export SLURM_CONF=$dir/slurm.conf
    if timeout 10 scancel --user="$(id -un)" 2> /dev/null; then
      for _ in $(seq 100); do
        [ -z "$(timeout 10 squeue -h -o %i 2> /dev/null || true)" ] && break
        sleep 0.1
      done
    fi
  fi
  for name in slurmd slurmctld munged; do
    [ -f "$dir/run/$name.pid" ] || continue
    pid=$(cat "$dir/run/$name.pid")
    # Only a process still running the program started here (a PID may have been reused).
    if [ -n "$pid" ] && grep -qs "$name" "/proc/$pid/cmdline"; then
      kill "$pid" 2> /dev/null || true
      for _ in $(seq 50); do
        kill -0 "$pid" 2> /dev/null || break
        sleep 0.1
      done
      if kill -0 "$pid" 2> /dev/null; then kill -KILL "$pid" 2> /dev/null || true; fi
    fi
    rm -f "$dir/run/$name.pid"
  done
}

# A TCP port on 127.0.0.1 that nothing listens on, from a range above the usual services.
free_port() {
  local p
  for _ in $(seq 200); do
    p=$((20000 + RANDOM % 20000))
    if ! (exec 3<> "/dev/tcp/127.0.0.1/$p") 2> /dev/null && [ "$p" != "${1:-}" ]; then
      echo "$p"
      return
    fi
  done
  echo "slurm-local: no free port found" >&2
  return 1
}

fail() {
  echo "slurm-local: $*" >&2
  local log
  for log in "$dir"/log/*.log; do
    [ -f "$log" ] && { echo "--- $log" >&2; tail -n 30 "$log" >&2; }
  done
  stop
  exit 1
}

case "$action" in
  stop)
    stop
    exit 0
    ;;
  start) ;;
  *) usage ;;
esac

for program in munged mungekey slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$program" > /dev/null || { echo "slurm-local: $program not found (scripts/install-deps.sh --slurm)" >&2; exit 1; }
done
[ "$(id -u)" -eq 0 ] || { echo "slurm-local: run as root (the daemons run as root here)" >&2; exit 1; }

mkdir -p "$dir"/{munge,run,log,state,spool}
chmod 700 "$dir" "$dir/munge"
mungekey --create --keyfile="$dir/munge/munge.key" --force
chmod 400 "$dir/munge/munge.key"
munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munged.seed" ||
  fail "munged did not start"

# This machine as slurmd sees it (sockets, cores, threads, memory in MB), named localhost.
node=$(slurmd -C | head -n 1 | sed -e 's/^NodeName=[^ ]*/NodeName=localhost NodeAddr=127.0.0.1/')
ctld_port=$(free_port)
slurmd_port=$(free_port "$ctld_port")
cat > "$dir/slurm.conf" << EOF
# A single-node cluster written by scripts/slurm-local.sh; everything lives in $dir.
ClusterName=certcyl-local
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=2
MinJobAge=600
$node
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
cat > "$dir/env.sh" << EOF
export SLURM_CONF=$dir/slurm.conf
EOF
export SLURM_CONF=$dir/slurm.conf

slurmctld -i || fail "slurmctld did not start"
slurmd -N localhost || fail "slurmd did not start"
for _ in $(seq 120); do
  state=$(sinfo -h -N -o %T 2> /dev/null | head -n 1 || true)
  case "$state" in
    idle*) echo "slurm-local: cluster up in $dir (SLURM_CONF=$dir/slurm.conf)"; exit 0 ;;
  esac
  sleep 0.5
done
fail "the node did not become idle within 60 s (state '${state:-unknown}')"
