#!/usr/bin/env bash
# A one-machine Slurm cluster (controller + one node on localhost) to try tray-farm and to run
# its tests: tools/slurm-local.sh start|stop|status|env.
#   start   installs Slurm and munge if missing (Debian packages, as root), writes a private
#           config under $TRAY_SLURM_DIR (default /tmp/tray-slurm) and starts munged,
#           slurmctld and slurmd; waits until the node is idle. Safe to run again.
#   stop    cancels the jobs, stops the three daemons by the pids they wrote (never by name).
#   status  prints whether each daemon runs; exit 0 only when all three do.
#   env     prints the export line clients need: eval "$(tools/slurm-local.sh env)".
# Every setting below is explained in ../shared/notes/slurm.md terms in docs/farm.md
# ("A cluster on one machine"). Needs root (the daemons run as root, no systemd).
set -euo pipefail

DIR=${TRAY_SLURM_DIR:-/tmp/tray-slurm}
CONF=$DIR/slurm.conf
CPUS=${TRAY_SLURM_CPUS:-$(nproc)}
PACKAGES=(slurmctld slurmd slurm-client munge)

say() { echo "slurm-local: $*" >&2; }
die() { say "error: $*"; exit 1; }

# The pid in FILE if that process is alive and runs PROGRAM (a stale pid file is not ours).
live_pid() {
  local file=$1 program=$2 pid
  [ -s "$file" ] || return 1
  pid=$(cat "$file")
  [ -r "/proc/$pid/cmdline" ] || return 1
  tr '\0' ' ' <"/proc/$pid/cmdline" | grep -q "$program" || return 1
  echo "$pid"
}

install_missing() {
  local missing=() p
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  [ "$(id -u)" -eq 0 ] || die "installing ${missing[*]} needs root (apt-get)"
  say "installing ${missing[*]}"
  apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" \
    >/dev/null || die "apt-get could not install ${missing[*]}"
}

write_config() {
  mkdir -p "$DIR"/{state,spool,log,munge}
  chmod 0755 "$DIR" "$DIR/munge"  # munged refuses a socket folder others cannot enter
  if [ ! -s "$DIR/munge/munge.key" ]; then
    mungekey --create --keyfile="$DIR/munge/munge.key" >/dev/null 2>&1 ||
      dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  fi
  chmod 0600 "$DIR/munge/munge.key"
  cat >"$CONF" <<EOF
# Written by tools/slurm-local.sh: a one-machine cluster, no accounting database.
ClusterName=tray-local
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
MailProg=/bin/true
ReturnToService=2
KillWait=${TRAY_SLURM_KILLWAIT:-30}
MinJobAge=300
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

start_daemons() {
  if ! live_pid "$DIR/munged.pid" munged >/dev/null; then
    munged --key-file="$DIR/munge/munge.key" --socket="$DIR/munge/munge.socket" \
      --pid-file="$DIR/munged.pid" --log-file="$DIR/log/munged.log" \
      --seed-file="$DIR/munge/munge.seed" --force 9>&- ||
      die "munged did not start (log: $DIR/log/munged.log)"
  fi
  if ! live_pid "$DIR/slurmctld.pid" slurmctld >/dev/null; then
    slurmctld -f "$CONF" 9>&- || die "slurmctld did not start (log: $DIR/log/slurmctld.log)"
  fi
  if ! live_pid "$DIR/slurmd.pid" slurmd >/dev/null; then
    slurmd -f "$CONF" 9>&- || die "slurmd did not start (log: $DIR/log/slurmd.log)"
  fi
  local i state
  for i in $(seq 1 150); do
    state=$(SLURM_CONF=$CONF sinfo -h -n localhost -o %T 2>/dev/null || true)
    case "$state" in
      idle* | mixed* | allocated*)
        say "up: node localhost $state ($CONF)"
        return 0
        ;;
      down* | drain*)  # left down or drained by an earlier run: return it to service
        SLURM_CONF=$CONF scontrol update NodeName=localhost State=RESUME 2>/dev/null || true
        ;;
    esac
    sleep 0.2
  done
  die "the node did not become idle in 30 s (state '${state:-none}'; logs: $DIR/log)"
}

stop_one() {
  local name=$1 pid i
  pid=$(live_pid "$DIR/$name.pid" "$name") || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for i in $(seq 1 100); do
    [ -d "/proc/$pid" ] || return 0
    sleep 0.1
  done
  kill -KILL "$pid" 2>/dev/null || true
}

case "${1:-}" in
  start)
    command -v apt-get >/dev/null || command -v slurmctld >/dev/null ||
      die "no apt-get and no Slurm: install slurmctld, slurmd, slurm-client and munge"
    install_missing
    [ "$(id -u)" -eq 0 ] || die "the daemons run as root here: run as root"
    mkdir -p "$DIR"
    # Two test runs starting at once start one cluster. The daemons must not inherit the lock's
    # descriptor (9>&- below): they would hold it for as long as they run.
    exec 9>"$DIR/start.lock" && flock 9
    write_config
    start_daemons
    ;;
  stop)
    if live_pid "$DIR/slurmctld.pid" slurmctld >/dev/null; then
      SLURM_CONF=$CONF scancel --full --quiet --user=root 2>/dev/null || true
    fi
    stop_one slurmd
    stop_one slurmctld
    stop_one munged
    say "stopped"
    ;;
  status)
    rc=0
    for d in munged slurmctld slurmd; do
      if pid=$(live_pid "$DIR/$d.pid" "$d"); then
        echo "$d: running (pid $pid)"
      else
        echo "$d: stopped"
        rc=1
      fi
    done
    exit $rc
    ;;
  env)
    echo "export SLURM_CONF=$CONF"
    ;;
  *)
    echo "usage: $0 start|stop|status|env" >&2
    exit 2
    ;;
esac
