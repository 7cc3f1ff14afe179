#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the cluster executor's tests (issue 21).
#
#   scripts/slurm-local.sh start    install slurm-wlm and munge from the Debian archive when
#                                   missing, write a private configuration, start munged,
#                                   slurmctld and slurmd, wait until the node takes jobs,
#                                   and print `SLURM_CONF=…` on stdout
#   scripts/slurm-local.sh stop     stop the daemons this script started
#   scripts/slurm-local.sh status   print `up` or `down` (exit status 0 or 1)
#   scripts/slurm-local.sh env      print `SLURM_CONF=…` (the cluster's configuration file)
#
# The cluster: one node (this host) with all its CPUs, one partition `arachis` (default),
# `proctrack/linuxproc` and `task/none` (no cgroups needed), no accounting database; finished
# jobs go to a job-completion log, `$SLURM_LOCAL_DIR/jobcomp.log`, which is the scheduler's
# record of every task that ran. Everything lives in $SLURM_LOCAL_DIR (default
# /tmp/arachis-slurm); the system's /etc/slurm is not touched, so clients find the cluster
# through SLURM_CONF.
#
# When the cluster cannot start (not root and no sudo, no package archive, a daemon that
# dies), `start` says why on stderr and exits with status 3, so callers can skip visibly.
set -euo pipefail

dir=${SLURM_LOCAL_DIR:-/tmp/arachis-slurm}
conf="$dir/slurm.conf"
command=${1:-start}

cannot() {
    echo "slurm-local.sh: cannot start a local Slurm cluster: $*" >&2
    exit 3
}

as_root=()
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || cannot "not root and no sudo"
    as_root=(sudo)
fi

install_packages() {
    if command -v slurmctld >/dev/null && command -v slurmd >/dev/null &&
        command -v sbatch >/dev/null && command -v munged >/dev/null; then
        return
    fi
    echo "installing slurm-wlm and munge from the Debian archive" >&2
    "${as_root[@]}" apt-get update -qq >&2 || cannot "apt-get update failed"
    DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq \
        --no-install-recommends slurm-wlm munge >&2 || cannot "apt-get install failed"
}

up() {
    [ -f "$conf" ] && SLURM_CONF="$conf" timeout 3 sinfo -h -o '%T' 2>/dev/null |
        grep -Eq '^(idle|mixed|allocated)'
}

# munged answers: a credential it makes, it can read back.
munge_ok() {
    munge -n 2>/dev/null | unmunge >/dev/null 2>&1
}

write_config() {
    local host cpus
    host=$(hostname -s)
    cpus=$(nproc)
    mkdir -p "$dir/state" "$dir/spool"
    cat > "$conf" <<EOF
# Written by scripts/slurm-local.sh: a one-node cluster for Arachis' tests.
ClusterName=arachis-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.log
MinJobAge=2
SchedulerParameters=sched_interval=1,bf_interval=1,sched_min_interval=0,batch_sched_delay=0
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=arachis Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
    if up; then
        echo "SLURM_CONF=$conf"
        return
    fi
    install_packages
    write_config
    if ! munge_ok; then
        [ -f /etc/munge/munge.key ] ||
            "${as_root[@]}" mungekey --create >&2 || cannot "no munge key and mungekey failed"
        "${as_root[@]}" mkdir -p /run/munge
        "${as_root[@]}" chown munge:munge /run/munge 2>/dev/null || true
        "${as_root[@]}" su -s /bin/sh munge -c munged >&2 ||
            "${as_root[@]}" munged --force >&2 || cannot "munged did not start"
        for _ in $(seq 20); do
            munge_ok && break
            sleep 0.25
        done
        munge_ok || cannot "munged started but does not answer (munge -n | unmunge)"
    fi
    "${as_root[@]}" env SLURM_CONF="$conf" slurmctld >&2 || cannot "slurmctld did not start"
    "${as_root[@]}" env SLURM_CONF="$conf" slurmd >&2 || cannot "slurmd did not start"
    for _ in $(seq 60); do
        if up; then
            echo "SLURM_CONF=$conf"
            return
        fi
        sleep 0.5
    done
    cannot "the node did not come up in 30 s (see $dir/slurmctld.log and $dir/slurmd.log)"
}

stop() {
    for daemon in slurmd slurmctld; do
        local pid_file="$dir/$daemon.pid"
        if [ -f "$pid_file" ]; then
            "${as_root[@]}" kill "$(cat "$pid_file")" 2>/dev/null || true
            rm -f "$pid_file"
        fi
    done
}

case "$command" in
    start) start ;;
    stop) stop ;;
    status) if up; then echo up; else echo down; exit 1; fi ;;
    env) echo "SLURM_CONF=$conf" ;;
    *) echo "usage: scripts/slurm-local.sh start|stop|status|env" >&2; exit 2 ;;
esac
