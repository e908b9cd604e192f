#!/usr/bin/env bash
# Starts and stops a throw-away single-node Slurm 22.05 cluster (munged,
# slurmctld, slurmd) that lives entirely in one folder, for tests of the
# Slurm job submission. Needs the Debian 12 packages slurm-wlm and munge; runs
# as root without systemd and writes nothing outside DIR (it only reads /etc).
#   scripts/tests/slurm-cluster.sh start DIR             # prints `export SLURM_CONF=DIR/slurm.conf`
#   scripts/tests/slurm-cluster.sh stop DIR              # idempotent, always exits 0
#   scripts/tests/slurm-cluster.sh conf-unreachable DIR  # a conf whose controller nothing answers
# Typical use: eval "$(scripts/tests/slurm-cluster.sh start "$tmp")"; sbatch ...; ... stop "$tmp"
set -euo pipefail

usage() { echo "usage: $0 start|stop|conf-unreachable DIR" >&2; exit 2; }
[[ $# -eq 2 ]] || usage
cmd="$1"
dir="$(realpath -m "$2")"

# Two free TCP ports, chosen by the kernel so that several clusters (or a stale
# one still in TIME_WAIT) never collide; the tiny race until the daemons bind is
# acceptable for tests.
free_ports() {
  python3 -c 'import socket; s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}

# ctld_port slurmd_port: the whole configuration, parameterised by DIR.
write_conf() {
  local node cpus mem_mb
  node="$(hostname -s)"
  cpus="$(nproc)"
  # slurmd drains a node whose configured RealMemory exceeds what it finds, so
  # stay below MemTotal.
  mem_mb=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) * 9 / 10240 ))
  # An empty SPANK stack, so that plugins other packages drop into
  # /etc/slurm/plugstack.conf.d cannot interfere.
  : >"$dir/plugstack.conf"
  # The cgroup plugins are only loaded for proctrack/cgroup, task/cgroup and
  # jobacct_gather/cgroup; linuxproc + task/none + jobacct_gather/none keep
  # slurmd away from /sys/fs/cgroup, which containers (and gVisor) rarely let
  # it manage. CR_CPU: each array task takes one CPU, so tasks run side by
  # side. AuthInfo socket= is read by both auth/munge and cred/munge (daemons
  # and the srun/sbatch/squeue/... clients, which all read this file).
  # A client retries a refused connection to the controller once a second for
  # MessageTimeout seconds: sbatch gives up after about 9 s with the default 10
  # (5 would fail faster, but risks timeouts on a loaded test machine).
  cat >"$dir/slurm.conf" <<EOF
ClusterName=hdhair-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$1
SlurmdPort=$2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
PlugStackConfig=$dir/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
MessageTimeout=10
KillWait=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$node MaxTime=INFINITE State=UP Default=YES
EOF
}

# True when PID still runs NAME of this cluster (its command line names DIR),
# so that a recycled pid or another cluster's daemon is never signalled.
ours() {
  local pid="$1" name="$2"
  [[ -r "/proc/$pid/comm" ]] && [[ "$(cat "/proc/$pid/comm" 2>/dev/null)" == "$name" ]] &&
    tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null | grep -qF "$dir/"
}

# slurmstepd processes of this cluster: their command line is just
# "slurmstepd: [job.step]", but they keep DIR/slurmd.log open. Builtins only:
# a fork per process makes this scan take seconds in a gVisor sandbox.
our_stepds() {
  local p comm fd
  for p in /proc/[0-9]*; do
    { read -r comm <"$p/comm"; } 2>/dev/null || continue
    [[ "$comm" == slurmstepd ]] || continue
    for fd in "$p"/fd/*; do
      [[ "$(readlink "$fd" 2>/dev/null)" == "$dir/"* ]] && { echo "${p#/proc/}"; break; }
    done
  done
  return 0
}

# Process ids in the subtrees below the given ones (a step's job processes).
descendants() {
  [[ $# -gt 0 ]] || return 0
  cat /proc/[0-9]*/stat 2>/dev/null | awk -v roots="$*" '
    { pid = $1; sub(/.*\) /, ""); parent[pid] = $2 }
    END { n = split(roots, q, " "); for (i = 1; i <= n; i++) want[q[i]] = 1
          do { more = 0
               for (p in parent) if (!(p in want) && (parent[p] in want)) { want[p] = 1; print p; more = 1 }
          } while (more) }'
}

# SIGTERM, up to 10 s grace, then SIGKILL.
terminate() {
  [[ $# -gt 0 ]] || return 0
  kill -TERM "$@" 2>/dev/null || true
  local p alive
  for _ in $(seq 100); do
    alive=0
    for p in "$@"; do kill -0 "$p" 2>/dev/null && alive=1; done
    [[ $alive -eq 0 ]] && return 0
    sleep 0.1
  done
  kill -KILL "$@" 2>/dev/null || true
}

stop() {
  local name pid pids=() ctld="" steps
  if [[ -f "$dir/pids" ]]; then
    while read -r name pid; do
      if ours "$pid" "$name"; then pids+=("$pid"); [[ $name == slurmctld ]] && ctld=$pid; fi
    done <"$dir/pids"
  fi
  # Cancel jobs while the controller still runs, so that slurmstepd ends the
  # steps itself (within KillWait); it ignores SIGTERM from us.
  if [[ -n "$ctld" ]]; then
    export SLURM_CONF="$dir/slurm.conf"
    timeout 10 squeue -h -o %A 2>/dev/null | timeout 10 xargs -r scancel >/dev/null 2>&1 || true
    for _ in $(seq 50); do [[ -z "$(our_stepds)" ]] && break; sleep 0.2; done
  fi
  # Whatever survived (e.g. the controller had died): the job processes get
  # SIGTERM and a grace period, their slurmstepd SIGKILL.
  steps="$(our_stepds)"
  # shellcheck disable=SC2046,SC2086 # word splitting of pid lists is intended
  terminate $(descendants $steps)
  # shellcheck disable=SC2086
  [[ -z "$steps" ]] || kill -KILL $steps 2>/dev/null || true
  # All daemons at once: each takes about 2 s to shut down, and none needs
  # another for that.
  terminate "${pids[@]}"
  rm -f "$dir/pids"
}

start() {
  # A second set of daemons would clobber the pids of the first (stop removes it).
  [[ ! -s "$dir/pids" ]] || { echo "slurm-cluster: $dir/pids exists; stop that cluster first" >&2; exit 1; }
  mkdir -p "$dir/state" "$dir/spool"
  # munged refuses a socket folder that others cannot traverse (mktemp -d is 0700).
  chmod 755 "$dir"
  [[ -f "$dir/munge.key" ]] || { dd if=/dev/urandom bs=1 count=1024 of="$dir/munge.key" status=none
                                 chmod 600 "$dir/munge.key"; }
  read -r ctld_port slurmd_port < <(free_ports)
  write_conf "$ctld_port" "$slurmd_port"
  : >"$dir/pids"
  # Foreground daemons so that $! is their real pid; munged -F logs to stderr.
  # --force: munged otherwise refuses group/world-writable parents of DIR.
  munged -F --force --socket="$dir/munge.socket" --key-file="$dir/munge.key" \
    --pid-file="$dir/munged.pid" --seed-file="$dir/munged.seed" </dev/null >>"$dir/munged.log" 2>&1 &
  echo "munged $!" >>"$dir/pids"
  for _ in $(seq 50); do [[ -S "$dir/munge.socket" ]] && break; sleep 0.1; done
  slurmctld -D -f "$dir/slurm.conf" </dev/null >>"$dir/slurmctld.out" 2>&1 &
  echo "slurmctld $!" >>"$dir/pids"
  slurmd -D -f "$dir/slurm.conf" </dev/null >>"$dir/slurmd.out" 2>&1 &
  echo "slurmd $!" >>"$dir/pids"
  echo "slurm-cluster: waiting up to 60 s for node $(hostname -s) to be idle in $dir" >&2
  local deadline=$((SECONDS + 60)) state="" name pid dead=""
  while ((SECONDS < deadline)) && [[ -z "$dead" ]]; do
    state="$(SLURM_CONF="$dir/slurm.conf" sinfo -h -o %T 2>/dev/null || true)"
    if [[ "$state" == idle ]]; then
      echo "export SLURM_CONF=$dir/slurm.conf"
      return 0
    fi
    # A daemon that died (bad configuration, port taken) will not come back.
    while read -r name pid; do kill -0 "$pid" 2>/dev/null || dead="$name"; done <"$dir/pids"
    sleep 0.5
  done
  echo "slurm-cluster: node not idle (state: '$state'${dead:+, $dead exited})" >&2
  # With -D the daemons log to stderr (*.out) as well; *.out alone also holds
  # what they print before their log file is open.
  local f
  for f in munged.log slurmctld.out slurmd.out; do
    [[ -s "$dir/$f" ]] && { echo "--- $dir/$f" >&2; tail -n 20 "$dir/$f" >&2; }
  done
  stop
  exit 1
}

case "$cmd" in
  start) start ;;
  stop) stop ;;
  conf-unreachable)
    mkdir -p "$dir"
    # Nothing listens on a port the kernel just handed out and took back.
    read -r ctld_port slurmd_port < <(free_ports)
    write_conf "$ctld_port" "$slurmd_port"
    echo "export SLURM_CONF=$dir/slurm.conf" ;;
  *) usage ;;
esac
