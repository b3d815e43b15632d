#!/usr/bin/env bash
# The SLURM path on a real SLURM: a throwaway single-node cluster (Debian's slurm-wlm and munge)
# under a temporary directory runs examples/slurm/sweep.sbatch as an array; its results.csv must
# equal the local sweep's byte for byte, also after one array task is cancelled mid-run and
# resubmitted. Then the guide's submitit recipe runs against the same cluster.
#
#   .ci/slurm.sh FUZZYMOTIV_BIN [VENV]     # VENV: a virtual environment with fuzzymotiv installed
#
# Needs root (or the packages already installed). Nothing is written under /etc: SLURM_CONF points
# at the temporary config, munge has its own socket and key; the daemons are stopped by their
# PIDs on exit. KEEP_SLURM_TMP=1 keeps the temporary directory (logs, sweep directories).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:?usage: .ci/slurm.sh FUZZYMOTIV_BIN [VENV]}")
VENV=${2:+$(realpath "$2")}
SWEEP=$PWD/.ci/sweep-ci.toml
SBATCH_SCRIPT=$PWD/examples/slurm/sweep.sbatch
export PATH="$(dirname "$BIN"):$PATH"   # sweep.sbatch calls `fuzzymotiv`; sbatch exports PATH

install_packages() {
    command -v slurmctld >/dev/null && command -v munged >/dev/null && return 0
    if ! command -v apt-get >/dev/null || [ "$(id -u)" -ne 0 ]; then
        echo "slurm: SKIPPED: slurm-wlm and munge are not installed, and apt-get cannot install" \
             "them here (needs Debian or Ubuntu, as root)"
        exit 0
    fi
    apt-get update -qq && apt-get install -y -qq slurm-wlm munge >/dev/null
}
install_packages

T=$(mktemp -d /tmp/fuzzymotiv-slurm.XXXXXX)
chmod 755 "$T"   # munged refuses a socket in a directory others cannot enter
export SLURM_CONF=$T/slurm.conf
PIDS=()
stop() {   # only what this script started, by PID
    local rc=$?
    [ -S "$T/munge/sock" ] && scancel --user "$(id -un)" 2>/dev/null || true
    # slurmstepd is not our child: wait for its socket in the spool directory to go
    for _ in $(seq 50); do compgen -G "$T/spool/localhost_*" >/dev/null || break; sleep 0.2; done
    for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do kill -TERM "${PIDS[i]}" 2>/dev/null || true; done
    for p in "${PIDS[@]}"; do wait "$p" 2>/dev/null || true; done
    if [ "$rc" = 0 ] && [ -z "${KEEP_SLURM_TMP:-}" ]; then rm -rf "$T"; else echo "slurm: kept $T"; fi
}
trap stop EXIT

start_munge() {
    mkdir -p -m 755 "$T/munge" "$T/state" "$T/spool" "$T/log"
    mungekey --create --keyfile="$T/munge/munge.key"
    munged -F --socket="$T/munge/sock" --key-file="$T/munge/munge.key" --pid-file="$T/munge/pid" \
        --log-file="$T/munge/log" --seed-file="$T/munge/seed" 2>"$T/log/munged.out" &
    PIDS+=($!)
    for _ in $(seq 50); do [ -S "$T/munge/sock" ] && break; sleep 0.1; done
}

write_conf() {   # localhost(127.0.0.1): no dependence on the hostname or DNS; no cgroups
    local hw user
    hw=$(slurmd -C | sed -n "1s/^NodeName=[^ ]* //p")
    user=$(id -un)
    cat >"$SLURM_CONF" <<EOF
ClusterName=fuzzymotiv-ci
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=${SLURMCTLD_PORT:-6817}
SlurmdPort=${SLURMD_PORT:-6818}
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/sock
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SchedulerParameters=batch_sched_delay=0
NodeName=localhost NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
}

start_slurm() {
    slurmctld -D >"$T/log/slurmctld.out" 2>&1 &
    PIDS+=($!)
    slurmd -D -N localhost >"$T/log/slurmd.out" 2>&1 &
    PIDS+=($!)
    for _ in $(seq 100); do
        sinfo -h -n localhost -o %t 2>/dev/null | grep -qx idle && return 0
        kill -0 "${PIDS[1]}" "${PIDS[2]}" 2>/dev/null || break   # a daemon died (port in use?)
        sleep 0.2
    done
    echo "slurm: the node never became idle" >&2
    tail -n 20 "$T"/log/*.log >&2
    exit 1
}

# sbatch the project's own array script: submit ARRAY OUT -> job id
submit() {
    sbatch --parsable --array="$1" -o "$T/log/sweep-%A_%a.out" "$SBATCH_SCRIPT" "$SWEEP" "$2"
}

# Waits for a job (all its array tasks) to leave the queue; sacct has no database here.
wait_gone() {
    for _ in $(seq 1500); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0; sleep 0.2; done
    echo "slurm: job $1 still queued after 5 minutes" >&2
    exit 1
}

# The states of a finished job's tasks, one "task I STATE" line each (scontrol keeps them 5 min).
states() {
    scontrol -o show job "$1" |
        sed -E 's/.*ArrayTaskId=([0-9]+).*JobState=([A-Z_]+).*/task \1 \2/' | sort -n -k2
}

same_results() {   # DIR LABEL: DIR/results.csv equals the local sweep's
    if cmp "$T/local/results.csv" "$1/results.csv"; then
        echo "slurm: $2: results.csv equals the local sweep's byte for byte"
    else
        echo "slurm: $2: results.csv differs from the local sweep's" >&2
        diff "$T/local/results.csv" "$1/results.csv" | head -n 20 >&2
        exit 1
    fi
}

start_munge
write_conf
start_slurm
echo "slurm: single-node cluster up ($(sinfo -h -o '%D node, %c CPUs, partition %P'))"

# The reference: the same sweep on this machine, without SLURM.
N=$(fuzzymotiv plan "$SWEEP" --count)
fuzzymotiv sweep "$SWEEP" --out "$T/local" --quiet
fuzzymotiv merge "$T/local" >/dev/null

# 1. The whole array.
J=$(submit "0-$((N - 1))" "$T/array")
wait_gone "$J"
states "$J"
[ "$(states "$J" | grep -c ' COMPLETED$')" = "$N" ] || { echo "slurm: not all $N tasks completed" >&2; exit 1; }
fuzzymotiv merge "$T/array" >/dev/null
same_results "$T/array" "array of $N tasks"

# 2. Cancel one task mid-run, at its first checkpoint, and resubmit it.
K=1
ID=$(fuzzymotiv plan "$SWEEP" | sed -n "$((K + 1))p" | sed -E 's/.*"id": *"([^"]+)".*/\1/')
CKPT=$T/cancel/jobs/$ID.partial/checkpoint.json
J=$(submit "0-$((N - 1))" "$T/cancel")
for _ in $(seq 3000); do [ -e "$CKPT" ] && break; sleep 0.05; done
[ -e "$CKPT" ] || { echo "slurm: task $K wrote no checkpoint ($CKPT)" >&2; exit 1; }
# Cancelled at once (SIGTERM to its processes, then SIGKILL). Not suspended first: a cancel that
# reaches the step before the suspend left the sweep stopped and still holding its job lock, so
# the resubmitted task waited on it for ever (seen once in five runs here).
scancel "${J}_$K"
wait_gone "$J"
states "$J"
states "$J" | grep -qx "task $K CANCELLED" || { echo "slurm: task $K was not cancelled" >&2; exit 1; }
[ ! -e "$T/cancel/jobs/$ID/DONE" ] && [ -e "$CKPT" ] ||
    { echo "slurm: task $K finished before it was cancelled: lengthen .ci/sweep-ci.toml" >&2; exit 1; }
echo "slurm: task $K cancelled once its checkpoint existed, before its end"
J2=$(submit "$K" "$T/cancel")
wait_gone "$J2"
states "$J2" | grep -qx "task $K COMPLETED" || { echo "slurm: resubmitted task $K failed" >&2; exit 1; }
grep -i "resum" "$T/log/sweep-${J2}_$K.out" | head -n 1 | sed 's/^/slurm: resubmitted task says: /'
fuzzymotiv merge "$T/cancel" >/dev/null
same_results "$T/cancel" "task $K cancelled and resubmitted"

# 3. ---- The guide's submitit recipe (docs/guide/sweeps-and-clusters.md), against the same cluster ----
RECIPE=examples/python/submitit_sweep.py
if [ ! -f "$RECIPE" ]; then
    echo "submitit recipe: $RECIPE not present (skipped)"
elif [ -z "$VENV" ]; then
    echo "submitit recipe: no virtual environment with fuzzymotiv given (skipped)"
else
    "$VENV/bin/pip" install --quiet "submitit==1.5.4"
    # submitit polls sacct, which has no database here: it warns "Bypassing sacct error" and
    # goes by the result files instead (checked with submitit 1.5.4); those lines go to the log.
    "$VENV/bin/python" "$RECIPE" "$SWEEP" "$T/submitit" --logs "$T/submitit-logs" \
        >"$T/log/submitit.out" 2>&1 || { tail -n 30 "$T/log/submitit.out" >&2; exit 1; }
    same_results "$T/submitit" "submitit recipe ($RECIPE)"
fi
