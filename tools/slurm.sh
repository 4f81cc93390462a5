#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, for the job-array runs of docs/batch-runs.md
# and their CI test (tests/cli/slurm_array_test.py):
#
#   tools/slurm.sh start  [--dir DIR] [--port P]   munged, slurmctld and slurmd on localhost; waits
#                                                  until sinfo shows the node idle
#   tools/slurm.sh stop   [--dir DIR]              stops the three daemons started from DIR
#   tools/slurm.sh status [--dir DIR]              each daemon's pid, the node's state; exit 1 when
#                                                  the cluster is not up
#   tools/slurm.sh env    [--dir DIR]              prints `export SLURM_CONF=DIR/slurm.conf`: the
#                                                  clients (sbatch, squeue, scancel, scontrol, sinfo)
#                                                  read it:  eval "$(tools/slurm.sh env)"
#
# Everything lives in DIR (default $SHADOWCERT_SLURM_DIR, else ${TMPDIR:-/tmp}/shadowcert-slurm):
# the munge key and socket, slurm.conf, the controller's state, the spool, the pid files and the
# logs (DIR/log/). Nothing under /etc, /run or /var is read or written, and no systemd is needed
# (a container is fine): the daemons are started as plain processes and found by their pid files.
# DIR and every folder above it must be enterable by everyone (munged refuses a socket that a
# client could not reach), and DIR/munge/munge.socket must fit a unix socket path (107 bytes).
# The node is `localhost` (slurmd -N) with this machine's CPUs and memory as `slurmd -C` reports
# them; one partition `batch` (the default); select/cons_tres over cores and memory, processes
# tracked by their parent pids (proctrack/linuxproc: no cgroups), no task plugin, no accounting
# database (so no sacct: a job's state is read with squeue and scontrol, which keeps finished jobs
# for MinJobAge, 3600 s here). P is slurmctld's port (default 6817), slurmd listens on P + 1.
#
# Run it as root (slurmd starts each job as the user who submitted it). Idempotent: start on a
# running cluster only waits for the node; stop on a stopped one does nothing. Needs Debian's
# slurm-wlm and munge (tools/dev.sh installs them). Exit 0 ok, 1 the cluster did not come up (the
# logs' tails are printed), 2 usage or a missing program.
set -euo pipefail

usage() {
  echo "usage: tools/slurm.sh start|stop|status|env [--dir DIR] [--port P]" >&2
  exit 2
}

[ $# -ge 1 ] || usage
ACTION=$1
shift
DIR=${SHADOWCERT_SLURM_DIR:-${TMPDIR:-/tmp}/shadowcert-slurm}
PORT=6817
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) [ $# -ge 2 ] || usage; DIR=$2; shift 2 ;;
    --port) [ $# -ge 2 ] || usage; PORT=$2; shift 2 ;;
    *) usage ;;
  esac
done
case "$PORT" in '' | *[!0-9]*) echo "tools/slurm.sh: --port must be a number, got '$PORT'" >&2; exit 2 ;; esac
mkdir -p "$DIR"
DIR=$(cd "$DIR" && pwd)
CONF=$DIR/slurm.conf
export SLURM_CONF=$CONF
START_TIMEOUT=${SHADOWCERT_SLURM_START_TIMEOUT:-60}

# The pid in FILE when that process is alive, else nothing (exit 1).
alive_pid() {
  local pid
  [ -f "$1" ] || return 1
  pid=$(cat "$1" 2>/dev/null) || return 1
  [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null || return 1
  echo "$pid"
}

require_programs() {
  local missing=()
  for p in munged slurmctld slurmd sinfo scontrol sbatch squeue scancel; do
    command -v "$p" >/dev/null 2>&1 || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "tools/slurm.sh: missing ${missing[*]} (Debian: apt-get install slurm-wlm munge; tools/dev.sh test installs them)" >&2
    exit 2
  fi
}

# This machine's node line as slurmd sees it (CPUs, boards, sockets, cores, threads, memory),
# named localhost. A little memory is kept back for the daemons and the system: a node whose
# RealMemory exceeds what slurmd measures at registration is drained.
node_line() {
  local line memory
  line=$(slurmd -C | head -n 1)
  memory=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$line")
  [ -n "$memory" ] || { echo "tools/slurm.sh: no RealMemory in 'slurmd -C': $line" >&2; exit 1; }
  line=$(sed -e 's/^NodeName=[^ ]*//' -e "s/RealMemory=[0-9]*/RealMemory=$((memory * 9 / 10))/" <<<"$line")
  echo "NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=localhost$line State=UNKNOWN"
}

write_conf() {
  local user
  user=$(id -un)
  cat >"$CONF.new" <<EOF
# Written by tools/slurm.sh: a single-node cluster on localhost (docs/batch-runs.md).
ClusterName=shadowcert
SlurmctldHost=localhost
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MinJobAge=3600
MaxArraySize=10001
$(node_line)
PartitionName=batch Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  mv "$CONF.new" "$CONF"
}

# The node's state as sinfo prints it (idle, mix, alloc, down*, drain, ...), or nothing.
node_state() {
  sinfo -h -n localhost -o %t 2>/dev/null | head -n 1 || true
}

print_logs() {
  for log in "$DIR"/log/munged.log "$DIR"/log/slurmctld.log "$DIR"/log/slurmd.log; do
    [ -f "$log" ] || continue
    echo "--- $log (last 15 lines)" >&2
    tail -n 15 "$log" >&2
  done
}

start_munged() {
  alive_pid "$DIR/munge/munged.pid" >/dev/null && return 0
  mkdir -p "$DIR/munge" "$DIR/log"
  # munged refuses a key that others may read, and a socket folder that others may write or
  # cannot enter (every client must reach the socket).
  chmod 755 "$DIR/munge"
  if [ ! -s "$DIR/munge/munge.key" ]; then
    dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  fi
  chmod 400 "$DIR/munge/munge.key"
  rm -f "$DIR/munge/munge.socket" "$DIR/munge/munge.socket.lock"
  munged --key-file="$DIR/munge/munge.key" --socket="$DIR/munge/munge.socket" \
    --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/log/munged.log" \
    --seed-file="$DIR/munge/munged.seed" --num-threads=2
}

start() {
  require_programs
  mkdir -p "$DIR/state" "$DIR/spool" "$DIR/log"
  start_munged
  if ! alive_pid "$DIR/slurmctld.pid" >/dev/null; then
    write_conf
    # -c: a fresh controller state (no jobs of an earlier cluster in this DIR to recover).
    slurmctld -c -f "$CONF"
  fi
  if ! alive_pid "$DIR/slurmd.pid" >/dev/null; then
    slurmd -f "$CONF" -N localhost
  fi
  local waited=0 state
  while :; do
    state=$(node_state)
    case "$state" in
      idle | mix | alloc | comp) break ;;
      drain* | drng | down | fail*)
        # ReturnToService=2 brings a node back on registration; a node left down by an earlier
        # run of this DIR is resumed once.
        scontrol update NodeName=localhost State=RESUME >/dev/null 2>&1 || true ;;
    esac
    if [ "$waited" -ge "$START_TIMEOUT" ]; then
      echo "tools/slurm.sh: the node did not come up within $START_TIMEOUT s (sinfo: '${state:-no answer}')" >&2
      print_logs
      exit 1
    fi
    sleep 1
    waited=$((waited + 1))
  done
  echo "slurm up in $DIR: node localhost $state ($(sinfo -h -n localhost -o '%c CPUs, %m MB')), partition batch, slurmctld port $PORT"
  echo "clients: export SLURM_CONF=$CONF"
}

# Stops the process in FILE (SIGTERM, then SIGKILL after 15 s), if it is alive.
stop_pid_file() {
  local pid waited=0
  pid=$(alive_pid "$1") || { rm -f "$1"; return 0; }
  kill "$pid" 2>/dev/null || true
  while kill -0 "$pid" 2>/dev/null; do
    if [ "$waited" -ge 150 ]; then
      kill -9 "$pid" 2>/dev/null || true
      break
    fi
    sleep 0.1
    waited=$((waited + 1))
  done
  rm -f "$1"
}

stop() {
  # Jobs first: a running job's slurmstepd outlives slurmd, so the jobs are cancelled and their
  # end awaited (at most 30 s) while the daemons still run; then slurmd, slurmctld, munged.
  if alive_pid "$DIR/slurmctld.pid" >/dev/null && command -v scancel >/dev/null 2>&1; then
    scancel --quiet --partition=batch 2>/dev/null || true
    local waited=0
    while [ -n "$(squeue -h -p batch -o %i 2>/dev/null)" ] && [ "$waited" -lt 300 ]; do
      sleep 0.1
      waited=$((waited + 1))
    done
  fi
  stop_pid_file "$DIR/slurmd.pid"
  stop_pid_file "$DIR/slurmctld.pid"
  stop_pid_file "$DIR/munge/munged.pid"
  echo "slurm stopped in $DIR"
}

status() {
  local up=0 pid
  for d in munge/munged slurmctld slurmd; do
    if pid=$(alive_pid "$DIR/$d.pid"); then
      echo "$(basename "$d"): running, pid $pid"
    else
      echo "$(basename "$d"): not running"
      up=1
    fi
  done
  [ -f "$CONF" ] && echo "node localhost: $(node_state)"
  return "$up"
}

case "$ACTION" in
  start) start ;;
  stop) stop ;;
  status) status ;;
  env) echo "export SLURM_CONF=$CONF" ;;
  *) usage ;;
esac
