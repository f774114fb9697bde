#!/usr/bin/env bash
# Sets up and starts a one-node Slurm cluster on this machine (Debian 12's slurm-wlm 22.05):
# munged for authentication, slurmctld and slurmd on localhost, one partition "local" with
# every CPU of this machine. For testing scripts/bench-slurm.sh (and any sbatch script) here.
#
# Usage (as root):
#   scripts/slurm-localhost.sh            # install, configure, start what is not running; wait
#                                         # until the node is idle; print sinfo
#   scripts/slurm-localhost.sh --restart  # stop the three daemons (by their pid files), start
#   scripts/slurm-localhost.sh --stop     # stop them
#   scripts/slurm-localhost.sh --status   # which daemons run, sinfo
#
# Idempotent: run it again at any time; it rewrites /etc/slurm/slurm.conf only when the
# machine's CPUs or memory (from `slurmd -C`) change, and then restarts the daemons.
# Without systemd (containers) it starts the daemons itself; their logs are in /var/log/slurm/
# and /var/log/munge/, their pid files in /run/. With systemd running it uses the Debian units
# munge, slurmctld and slurmd through systemctl instead (that path is not tested in CI's
# container, which has no systemd). No cgroups: ProctrackType=proctrack/linuxproc,
# TaskPlugin=task/none, no accounting database. Not for a shared or production cluster.
set -euo pipefail

CONF=/etc/slurm/slurm.conf
PARTITION=local
MARK="# Written by kautham's scripts/slurm-localhost.sh"

action=start
case "${1:-}" in
  "") ;;
  --restart) action=restart ;;
  --stop) action=stop ;;
  --status) action=status ;;
  -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "slurm-localhost: unknown option $1 (see --help)" >&2; exit 2 ;;
esac

if [ "$(id -u)" -ne 0 ]; then
  echo "slurm-localhost: run as root (it installs packages, writes /etc/slurm, starts daemons)" >&2
  exit 2
fi

log() { echo "slurm-localhost: $*"; }

# A daemon runs if its pid file names a live process.
running() {  # pidfile
  [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null
}

SYSTEMD=0
[ -d /run/systemd/system ] && command -v systemctl >/dev/null 2>&1 && SYSTEMD=1

unit() { case $1 in munged) echo munge ;; *) echo "$1" ;; esac; }

start_daemon() {  # name
  log "starting $1"
  if [ $SYSTEMD -eq 1 ]; then
    systemctl enable --now "$(unit "$1")" >/dev/null 2>&1 || systemctl start "$(unit "$1")"
  elif [ "$1" = munged ]; then
    runuser -u munge -- /usr/sbin/munged
  else
    "/usr/sbin/$1"
  fi
}

stop_daemon() {  # name pidfile
  if [ $SYSTEMD -eq 1 ]; then
    systemctl is-active --quiet "$(unit "$1")" && log "stopping $1" &&
      systemctl stop "$(unit "$1")"
    return 0
  fi
  if running "$2"; then
    local pid
    pid=$(cat "$2")
    log "stopping $1 (pid $pid)"
    kill "$pid"
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    if kill -0 "$pid" 2>/dev/null; then
      log "$1 (pid $pid) did not stop; killing it"
      kill -9 "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$2"
}

status() {
  for d in munged:/run/munge/munged.pid slurmctld:/run/slurmctld.pid slurmd:/run/slurmd.pid; do
    if running "${d#*:}"; then
      log "${d%%:*} runs (pid $(cat "${d#*:}"))"
    else
      log "${d%%:*} does not run"
    fi
  done
  if running /run/slurmctld.pid; then sinfo || true; fi
}

stop_all() {
  stop_daemon slurmd /run/slurmd.pid
  stop_daemon slurmctld /run/slurmctld.pid
  stop_daemon munged /run/munge/munged.pid
}

case $action in
  status) status; exit 0 ;;
  stop) stop_all; exit 0 ;;
  restart) stop_all ;;
esac

# 1. Packages
missing=()
for pkg in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  log "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# 2. Munge: a key readable by munge only, then munged as the munge user
if [ ! -s /etc/munge/munge.key ]; then
  log "creating /etc/munge/munge.key"
  mungekey --create --keyfile=/etc/munge/munge.key
fi
chown munge:munge /etc/munge /etc/munge/munge.key
chmod 0700 /etc/munge
chmod 0400 /etc/munge/munge.key
install -d -o munge -g munge -m 0755 /run/munge
install -d -o munge -g munge -m 0700 /var/lib/munge /var/log/munge
if ! running /run/munge/munged.pid; then
  start_daemon munged
fi
for _ in $(seq 50); do munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
munge -n </dev/null | unmunge >/dev/null || { log "munge does not work: see /var/log/munge/munged.log"; exit 1; }

# 3. slurm.conf from what slurmd sees (CPUs, sockets, cores, threads, memory)
host=$(hostname -s)
node=$(slurmd -C | head -n 1)      # NodeName=vm CPUs=2 Boards=1 ... RealMemory=24105
case $node in
  "NodeName=$host "*) ;;
  *) log "unexpected 'slurmd -C' output: $node"; exit 1 ;;
esac
# Leave the system 5 % of the memory (at least 256 MB): jobs may not ask for all of it.
realmem=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$node")
spare=$(( realmem / 20 > 256 ? realmem / 20 : 256 ))
node=${node/RealMemory=$realmem/RealMemory=$((realmem - spare))}
new=$(cat <<EOF
$MARK: a one-node cluster on localhost.
# Rerun that script after a change of the machine; edit by hand at your own risk.
ClusterName=localhost
SlurmctldHost=$host(127.0.0.1)
AuthType=auth/munge
CredType=cred/munge
SlurmUser=slurm
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
# No cgroups (they need not work in a container): processes are tracked through /proc.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
# CPUs are the consumable resource; memory is not tracked, so jobs without --mem share it.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
SlurmdTimeout=300
InactiveLimit=0
KillWait=30
MinJobAge=300
MaxArraySize=10001
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=$PARTITION Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
)
changed=0
if [ ! -f "$CONF" ] || [ "$(cat "$CONF")" != "$new" ]; then
  if [ -f "$CONF" ] && ! grep -q "^$MARK" "$CONF"; then
    cp -p "$CONF" "$CONF.before-slurm-localhost"
    log "kept the previous $CONF as $CONF.before-slurm-localhost"
  fi
  printf '%s\n' "$new" >"$CONF"
  chmod 0644 "$CONF"
  log "wrote $CONF"
  changed=1
fi
install -d -o slurm -g slurm -m 0755 /var/spool/slurmctld /var/log/slurm
install -d -o root -g root -m 0755 /var/spool/slurmd

# 4. The daemons: restarted if the configuration changed, started if not running
if [ $changed -eq 1 ]; then
  stop_daemon slurmd /run/slurmd.pid
  stop_daemon slurmctld /run/slurmctld.pid
fi
if ! running /run/slurmctld.pid; then
  start_daemon slurmctld
fi
for _ in $(seq 100); do scontrol ping 2>/dev/null | grep -q UP && break; sleep 0.2; done
scontrol ping | grep -q UP || { log "slurmctld does not answer: see /var/log/slurm/slurmctld.log"; exit 1; }
if ! running /run/slurmd.pid; then
  start_daemon slurmd
fi

# 5. Wait for the node to be usable; a node left down or drained by an earlier run is resumed.
state=""
for _ in $(seq 100); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null | head -n 1)
  case $state in
    idle|mix|alloc) break ;;
    down*|drain*|drng*|fail*)
      scontrol update NodeName="$host" State=RESUME 2>/dev/null || true ;;
  esac
  sleep 0.3
done
case $state in
  idle|mix|alloc) ;;
  *) log "node $host is '$state': see /var/log/slurm/slurmd.log and 'scontrol show node $host'"
     exit 1 ;;
esac
status
