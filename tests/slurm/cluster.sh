#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for tests/slurm/run_test.sh: a munge daemon with a key of its own, the
# controller (slurmctld) and the node daemon (slurmd) on localhost, configured from tests/slurm/slurm.conf.in, every
# file under DIR. Nothing of the machine's own munge or Slurm setup is read or changed.
#   bash tests/slurm/cluster.sh start DIR   # then: export SLURM_CONF=DIR/slurm.conf
#   bash tests/slurm/cluster.sh stop DIR
# Needs root (slurmd starts jobs as their users) and Debian's slurm-wlm and munge (scripts/install-debian-packages.sh).
set -euo pipefail
command=${1:-} dir=${2:-}
[ -n "$command" ] && [ -n "$dir" ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)

stop_daemon() {  # the daemon whose pid file is $1, then wait for it to go
  [ -f "$1" ] || return 0
  local pid
  pid=$(cat "$1")
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.2; done
  kill -9 "$pid" 2>/dev/null || true
}

case $command in
start)
  [ "$(id -u)" -eq 0 ] || { echo "cluster.sh: slurmd must start as root (it starts jobs as their users)" >&2; exit 1; }
  for program in munged slurmctld slurmd sbatch; do
    command -v "$program" > /dev/null ||
      { echo "cluster.sh: $program is missing: apt-get install slurm-wlm munge" >&2; exit 1; }
  done
  mkdir -p "$dir"/munge "$dir"/state "$dir"/spool
  dir=$(cd "$dir" && pwd)
  chmod 700 "$dir"/munge
  # A key of its own: the test cluster trusts no one else's credentials, and no one else trusts its.
  head -c 1024 /dev/urandom > "$dir"/munge/munge.key
  chmod 600 "$dir"/munge/munge.key
  munged --force --key-file="$dir"/munge/munge.key --socket="$dir"/munge/munge.socket \
    --pid-file="$dir"/munge/munged.pid --log-file="$dir"/munge/munged.log --seed-file="$dir"/munge/munged.seed
  host=$(hostname -s)
  memory_mb=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 * 9 / 10 ))
  # Ports away from Slurm's defaults (6817, 6818), so that a machine's own cluster is left alone.
  sed -e "s|@DIR@|$dir|g" -e "s|@HOST@|$host|g" -e "s|@CPUS@|$(nproc)|g" -e "s|@MEMORY_MB@|$memory_mb|g" \
      -e "s|@CTLD_PORT@|${RCSPLAT_SLURMCTLD_PORT:-16817}|g" -e "s|@SLURMD_PORT@|${RCSPLAT_SLURMD_PORT:-16818}|g" \
      "$here"/slurm.conf.in > "$dir"/slurm.conf
  export SLURM_CONF="$dir"/slurm.conf
  slurmctld -i
  slurmd
  for _ in $(seq 150); do
    state=$(sinfo -h -N -o %T 2>/dev/null | head -1 || true)
    [ "$state" = idle ] && exit 0
    sleep 0.2
  done
  echo "cluster.sh: the node did not come up (state '${state:-none}'); logs in $dir" >&2
  tail -5 "$dir"/slurmctld.log "$dir"/slurmd.log >&2 || true
  exit 1
  ;;
stop)
  [ -d "$dir" ] || exit 0
  stop_daemon "$dir"/slurmd.pid
  stop_daemon "$dir"/slurmctld.pid
  stop_daemon "$dir"/munge/munged.pid
  ;;
*)
  echo "usage: $0 start|stop DIR" >&2
  exit 2
  ;;
esac
