#!/usr/bin/env bash
# local_slurm.sh - a private, single-node Slurm cluster on localhost, for tests.
#
#   local_slurm.sh start DIR   # prints "export SLURM_CONF=DIR/slurm/slurm.conf"
#   local_slurm.sh stop DIR    # idempotent; only touches daemons started for DIR
#
# Design:
# - Everything lives under DIR: a fresh munge key, munged's socket/pid/log/seed,
#   slurm.conf + cgroup.conf, StateSaveLocation, SlurmdSpoolDir, pid and log
#   files. Nothing under /etc/munge, /etc/slurm or /run is read or written, no
#   system service is touched. Clients find the cluster via SLURM_CONF.
# - Slurm talks to *our* munged through AuthInfo=socket=... (in 22.05 that one
#   setting serves both auth/munge and cred/munge).
# - Daemons run in the foreground (-F / -D) as background jobs of this script,
#   with their stdio sent to DIR/log, so the pid is known the moment they start
#   (a start that fails halfway can still be stopped) and a caller doing
#   eval "$(local_slurm.sh start DIR)" is not kept waiting on an open pipe.
#   Pids are recorded in DIR/run/<daemon>.pid. Every daemon also carries the
#   environment marker LOCAL_SLURM_DIR=DIR, and `stop` only signals a pid whose
#   /proc/<pid>/environ carries that exact marker, so a reused pid or a foreign
#   daemon is never killed.
# - `stop` first scancels all jobs (so no job outlives the cluster), then TERMs
#   slurmd, slurmctld, munged (KILL after a grace period), and finally KILLs
#   leftovers: marked processes, and processes holding DIR/log/slurmd.log or a
#   DIR/slurm/spool file open (slurmstepd overwrites its environ with its
#   process title, so it has no visible marker), plus their descendants.
# - slurm.conf choices:
#     SlurmctldHost/NodeName = hostname -s, addressed as 127.0.0.1 (no DNS);
#     ports = random free ports in 20000-40000 (parallel clusters don't clash);
#     CPUs = nproc, RealMemory = half of MemTotal (must not exceed the real
#       value, or slurmd registers the node as invalid);
#     SlurmUser=root (we are root in a container);
#     ProctrackType=proctrack/linuxproc + TaskPlugin=task/none +
#       JobAcctGatherType=jobacct_gather/none: no cgroups needed;
#     select/cons_tres with CR_Core: several 1-core jobs/array tasks share
#       the node at once;
#     ReturnToService=2: node becomes usable as soon as slurmd registers;
#     AccountingStorageType=accounting_storage/none: no slurmdbd;
#     MpiDefault=none, MailProg=/bin/true: no external dependencies;
#     KillWait / cred_expire short: cancels, stop and requeue are quick
#       (a requeued job only becomes eligible cred_expire+1 s later);
#     sched_interval/bf_interval=1: jobs whose begin time or dependency was
#       just satisfied start within ~1 s instead of waiting up to 30-60 s.
#   cgroup.conf: slurmd 22.05 always loads a cgroup plugin at startup, even
#   with the plugins above (which create no cgroups); there is no "disabled"
#   value before 23.x. cgroup/v2 is fatal on a hybrid v1/v2 host ("Hybrid mode
#   is not supported"), so keep autodetect; IgnoreSystemdOnFailure=yes lets
#   cgroup/v2 hosts without systemd/dbus (containers) get past init.
# - slurmctld runs with -c (clear state): a stale state dir never matters.
set -euo pipefail

readonly PROG=${0##*/}
readonly START_TIMEOUT=${LOCAL_SLURM_START_TIMEOUT:-60}
readonly STOP_GRACE=${LOCAL_SLURM_STOP_GRACE:-5}

die() { echo "$PROG: error: $*" >&2; exit 1; }
log() { echo "$PROG: $*" >&2; }

# Absolute path of DIR (DIR need not exist yet).
abs_dir() {
    local d=$1
    [[ $d == /* ]] || d="$PWD/$d"
    echo "${d%/}"
}

# True if TCP port $1 appears in the kernel's socket tables (any state).
port_in_use() {
    local hex
    hex=$(printf ':%04X ' "$1")
    grep -qi -- "$hex" /proc/net/tcp /proc/net/tcp6 2>/dev/null
}

# Print a random TCP port in 20000-40000 that is not in use and not $1.
pick_port() {
    local avoid=${1:-0} port i
    for ((i = 0; i < 200; i++)); do
        port=$((20000 + (RANDOM * 32768 + RANDOM) % 20001))
        if [[ $port != "$avoid" ]] && ! port_in_use "$port"; then
            echo "$port"
            return 0
        fi
    done
    die "no free TCP port found in 20000-40000"
}

# Print the last lines of a daemon's log files (for error messages).
show_logs() {
    local name=$1 f n
    # $name.log is the daemon's log file, $name.out its stdout/stderr (which
    # alone holds errors from before the log file was opened).
    for f in "$D/log/$name.log" "$D/log/$name.out"; do
        [[ -s $f ]] || continue
        [[ $f == *.log ]] && n=20 || n=10
        echo "---- last $n lines of $f ----" >&2
        tail -n "$n" "$f" >&2
    done
}

# Fail with the daemon's name and log tail.
daemon_failed() {
    local name=$1
    shift
    echo "$PROG: error: $name: $*" >&2
    # The controller decides the node's state, so its log explains slurmd's.
    if [[ $name == slurmd ]]; then show_logs slurmctld; fi
    show_logs "$name"
    exit 1
}

# True if pid $1 is alive and carries our marker for $D.
ours() {
    local pid=$1
    [[ $pid =~ ^[0-9]+$ ]] || return 1
    grep -qzxF "LOCAL_SLURM_DIR=$D" "/proc/$pid/environ" 2>/dev/null
}

# Start "$@" in the background as daemon $name; record its pid. Descriptors
# above 2 are closed so the daemon holds no pipe of the caller (e.g. a test
# harness reading our output) open; the subshell execs, so $! is the daemon.
launch() {
    local name=$1
    shift
    (
        for fd in /proc/self/fd/*; do
            fd=${fd##*/}
            if ((fd > 2)); then eval "exec $fd>&-"; fi
        done
        LOCAL_SLURM_DIR=$D exec "$@"
    ) </dev/null >"$D/log/$name.out" 2>&1 &
    echo $! >"$D/run/$name.pid"
}

# Wait (up to $3 s) until command $2 succeeds; on failure name daemon $1 and
# add the output of the optional command $4.
wait_for() {
    local name=$1 check=$2 timeout=$3 pid deadline=$((SECONDS + $3))
    pid=$(<"$D/run/$name.pid")
    until $check; do
        ours "$pid" || daemon_failed "$name" "exited during startup"
        ((SECONDS < deadline)) || daemon_failed "$name" "not ready after ${timeout}s${4:+ ($($4))}"
        sleep 0.2
    done
}

munge_ready() { munge -n --socket="$D/munge/munge.socket" </dev/null >/dev/null 2>&1; }
ctld_ready() { SLURM_CONF=$D/slurm/slurm.conf scontrol ping 2>/dev/null | grep -q 'is UP'; }

# Node state as sinfo reports it (e.g. "idle", "down*", "unk*").
node_state() {
    SLURM_CONF=$D/slurm/slurm.conf sinfo -h -N -n "$NODE" -o '%T' 2>/dev/null | head -n1
}
node_idle() { [[ $(node_state) == idle ]]; }
describe_node() { echo "node $NODE is '$(node_state)', not idle"; }

write_slurm_conf() {
    local cpus mem ctld_port slurmd_port
    cpus=$(nproc)
    mem=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 / 2 }' /proc/meminfo)
    ((mem >= 1)) || mem=1
    ctld_port=$(pick_port)
    slurmd_port=$(pick_port "$ctld_port")
    cat >"$D/slurm/slurm.conf" <<EOF
# Generated by $PROG for a private test cluster; see the script for rationale.
ClusterName=localtest
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge/munge.socket,cred_expire=10
StateSaveLocation=$D/slurm/state
SlurmdSpoolDir=$D/slurm/spool
SlurmctldPidFile=$D/run/slurmctld.daemon.pid
SlurmdPidFile=$D/run/slurmd.daemon.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1
ReturnToService=2
MpiDefault=none
MailProg=/bin/true
KillWait=2
MinJobAge=30
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
    cat >"$D/slurm/cgroup.conf" <<EOF
# slurmd loads a cgroup plugin even though proctrack/linuxproc + task/none
# create no cgroups; see $PROG for why these two settings.
CgroupPlugin=autodetect
IgnoreSystemdOnFailure=yes
EOF
}

start_munged() {
    mungekey --create --keyfile="$D/munge/munge.key" >/dev/null 2>&1 ||
        dd if=/dev/urandom of="$D/munge/munge.key" bs=1024 count=1 status=none
    chmod 400 "$D/munge/munge.key"
    launch munged munged --foreground --force \
        --key-file="$D/munge/munge.key" --socket="$D/munge/munge.socket" \
        --pid-file="$D/run/munged.daemon.pid" --log-file="$D/log/munged.log" \
        --seed-file="$D/munge/munged.seed"
    wait_for munged munge_ready 15
}

start_slurm() {
    local conf=$D/slurm/slurm.conf
    launch slurmctld slurmctld -D -c -f "$conf"
    wait_for slurmctld ctld_ready 30
    launch slurmd slurmd -D -f "$conf"
    wait_for slurmd node_idle "$START_TIMEOUT" describe_node
}

# EXIT trap of cmd_start: a failed start stops what it had launched.
on_start_exit() {
    local rc=$?
    trap - EXIT
    if ((rc != 0)); then
        log "start failed; stopping what was started under $D"
        cmd_stop || true
    fi
    exit "$rc"
}

cmd_start() {
    local t0=$SECONDS
    [[ ! -e $D/run ]] || die "$D/run exists; run '$PROG stop $D' first or use a fresh DIR"
    mkdir -p "$D"/{munge,run,log} "$D"/slurm/{state,spool}
    trap on_start_exit EXIT
    trap 'exit 130' INT TERM
    chmod 755 "$D/munge" # munged warns unless all may reach the socket
    NODE=$(hostname -s)
    write_slurm_conf
    start_munged
    start_slurm
    trap - EXIT INT TERM
    log "cluster up in $((SECONDS - t0))s (node $NODE idle)"
    echo "export SLURM_CONF=$D/slurm/slurm.conf"
}

# Cancel all jobs while the controller is still up, so no job outlives stop.
cancel_jobs() {
    local pid ids i
    pid=$(cat "$D/run/slurmctld.pid" 2>/dev/null) || return 0
    ours "$pid" || return 0
    export SLURM_CONF=$D/slurm/slurm.conf
    ids=$(squeue -h -o %i 2>/dev/null) || return 0
    [[ -n $ids ]] || return 0
    # shellcheck disable=SC2086 # word splitting of the id list is intended
    scancel --quiet $ids 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do
        [[ -n $(squeue -h -o %i 2>/dev/null) ]] || return 0
        sleep 0.2
    done
    log "jobs still listed after scancel; stopping daemons anyway"
}

# TERM the pid in $D/run/$1.pid if it is ours; KILL after STOP_GRACE seconds.
stop_daemon() {
    local name=$1 pidfile=$D/run/$1.pid pid i
    [[ -f $pidfile ]] || return 0
    pid=$(<"$pidfile")
    if ours "$pid"; then
        kill -TERM "$pid" 2>/dev/null || true
        for ((i = 0; i < STOP_GRACE * 10; i++)); do
            ours "$pid" || break
            sleep 0.1
        done
        if ours "$pid"; then
            log "$name (pid $pid) ignored SIGTERM for ${STOP_GRACE}s; sending SIGKILL"
            kill -KILL "$pid" 2>/dev/null || true
            while ours "$pid"; do sleep 0.1; done
        fi
    fi
    rm -f "$pidfile"
}

# Print the pids in $1 (space separated) plus all their descendants, minus
# this script and its ancestors (the caller is never a victim).
with_descendants() {
    ps -e -o pid=,ppid= | awk -v roots="$1" -v self="$$" '
        { parent[$1] = $2 }
        END {
            n = split(roots, r, " "); for (i = 1; i <= n; i++) keep[r[i]] = 1
            do { added = 0
                 for (p in parent) if (!(p in keep) && (parent[p] in keep)) {
                     keep[p] = 1; added = 1 } } while (added)
            for (p = self; p > 1; p = parent[p]) delete keep[p]
            for (p in keep) print p
        }'
}

# Pids of processes that belong to this cluster but may have no pid file:
# those with our environment marker (daemons), and those holding slurmd's log
# or a spool file open (slurmstepd overwrites its environ for its title).
cluster_pids() {
    local p pid
    for p in /proc/[0-9]*; do
        pid=${p#/proc/}
        if ours "$pid"; then echo "$pid"; fi
    done
    find /proc/[0-9]*/fd -mindepth 1 -maxdepth 1 \( -lname "$D/log/slurmd.log" \
        -o -lname "$D/slurm/spool/*" \) 2>/dev/null | cut -d/ -f3 || true
}

# Kill leftovers (e.g. jobs of a controller that was already dead, so they
# could not be cancelled) together with their children (job scripts).
kill_strays() {
    local roots pids
    roots=$(cluster_pids | sort -u | tr '\n' ' ')
    [[ -n ${roots// /} ]] || return 0
    pids=$(with_descendants "$roots" | tr '\n' ' ')
    [[ -n ${pids// /} ]] || return 0
    log "killing leftover processes: $pids"
    # shellcheck disable=SC2086 # word splitting of the pid list is intended
    kill -KILL $pids 2>/dev/null || true
}

cmd_stop() {
    [[ -d $D ]] || return 0
    cancel_jobs
    stop_daemon slurmd
    stop_daemon slurmctld
    stop_daemon munged
    kill_strays
    rm -f "$D/munge/munge.socket" "$D/munge/munge.socket.lock"
    rmdir "$D/run" 2>/dev/null || true
}

main() {
    (($# == 2)) || die "usage: $PROG start|stop DIR"
    D=$(abs_dir "$2")
    case $1 in
        start) cmd_start ;;
        stop) cmd_stop ;;
        *) die "unknown command '$1' (expected start or stop)" ;;
    esac
}

main "$@"
