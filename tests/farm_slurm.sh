#!/usr/bin/env bash
# prism farm on a real Slurm: a single-node cluster (munge + slurmctld + slurmd on loopback, all
# state in a private directory) runs the Cornell box as a job array plus the merge job.
#   1. by samples (4 array tasks): the merged image equals the single-process render
#   2. by tiles (4 array tasks): the same
#   3. one task fails: the merge never runs, `prism farm status` names the task and its error;
#      fixed and submitted again, only that task runs and the merge completes
# Starts and stops only the daemons it started (by PID) and leaves nothing running.
# Exit 77 (skipped) where Slurm cannot start here: not root, packages missing, daemons not coming up.
# Usage: farm_slurm.sh PRISM SOURCE_DIR WORK_DIR
set -euo pipefail
PRISM=$1
SRC=$2
WORK=$3

skip() { echo "SKIPPED: $*"; exit 77; }
[[ $(id -u) -eq 0 ]] || skip "the single-node Slurm cluster needs root (slurmd runs jobs as their user)"
for p in munged slurmctld slurmd sbatch scontrol squeue scancel sinfo; do
  command -v "$p" >/dev/null || [[ -x /usr/sbin/$p ]] || skip "$p is not installed (Debian packages slurm-wlm and munge)"
done

rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
# The daemons' state lives in a short private path: munge's socket path must fit a sockaddr_un,
# and every directory on it must be o+x.
D=$(mktemp -d /tmp/prism-slurm.XXXXXX)
chmod 755 "$D"
mkdir -p "$D"/{munge,state,spool/slurmd,log}
chmod 755 "$D/munge"
head -c 1024 /dev/urandom >"$D/munge/munge.key"
chmod 400 "$D/munge/munge.key"

# Ports of this run's own (not Slurm's default 6817/6818, so a system Slurm cannot clash).
PORT=${PRISM_SLURM_PORT:-$((20000 + ($$ % 20000) * 2))}
CPUS=$(nproc)
MEM=$(awk '/MemAvailable/{print int($2/1024*0.5)}' /proc/meminfo)
cat >"$D/slurm.conf" <<CONF
ClusterName=prismtest
SlurmctldHost=localhost
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge/munge.socket
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool/slurmd
SlurmctldPidFile=$D/state/slurmctld.pid
SlurmdPidFile=$D/spool/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=3600
MailProg=/bin/true
PlugStackConfig=$D/plugstack.conf
SchedulerParameters=batch_sched_delay=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM State=UNKNOWN
PartitionName=render Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
# No DependencyParameters=kill_invalid_depend: prism farm submit must ask for
# --kill-on-invalid-dep=yes itself, as on a cluster configured with Slurm's defaults.
: >"$D/plugstack.conf"
export SLURM_CONF=$D/slurm.conf

PIDS=()
cleanup() {
  set +e
  # Jobs first: slurmstepd and a job's processes outlive slurmd.
  scancel --user=root 2>/dev/null
  for _ in $(seq 1 80); do [[ -z $(squeue -h 2>/dev/null) ]] && break; sleep 0.25; done
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${PIDS[@]}"; do
    for _ in $(seq 1 40); do kill -0 "$p" 2>/dev/null || break; sleep 0.25; done
    if kill -0 "$p" 2>/dev/null; then echo "daemon $p did not stop: SIGKILL"; kill -9 "$p"; fi
  done
  # Anything of this cluster still alive (an orphaned slurmstepd) would point at $D.
  local left
  left=$(pgrep -f "$D" || true)
  [[ -n $left ]] && { echo "left running: $left: SIGKILL"; kill -9 $left 2>/dev/null; }
  [[ ${#PIDS[@]} -gt 0 ]] && echo "stopped the daemons this test started: ${PIDS[*]}"
  rm -rf "$D"
}
trap cleanup EXIT

munged --key-file="$D/munge/munge.key" --socket="$D/munge/munge.socket" --pid-file="$D/munge/munged.pid" \
  --seed-file="$D/munge/munged.seed" --log-file="$D/log/munged.log" || skip "munged does not start: $(tail -n 3 "$D/log/munged.log")"
PIDS+=("$(cat "$D/munge/munged.pid")")
setsid "$(command -v slurmctld || echo /usr/sbin/slurmctld)" -D -f "$SLURM_CONF" >"$D/log/slurmctld.out" 2>&1 &
PIDS+=("$!")
setsid "$(command -v slurmd || echo /usr/sbin/slurmd)" -D -N localhost -f "$SLURM_CONF" >"$D/log/slurmd.out" 2>&1 &
PIDS+=("$!")
state=
for _ in $(seq 1 120); do
  state=$(sinfo -h -N -o '%T' 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.25
done
if [[ $state != idle ]]; then
  tail -n 5 "$D"/log/*.log "$D"/log/*.out 2>/dev/null || true
  skip "the Slurm node did not become idle within 30 s (state '$state')"
fi
echo "Slurm up: munged, slurmctld, slurmd (pids ${PIDS[*]}), port $PORT, $CPUS CPUs"

cd "$WORK"
# job_file NAME OUTPUT [KEYS]: the Cornell box at 96x72, 32 spp, float, with three AOVs
job_file() {
  printf '{"scene": "%s", "output": "%s", "resolution": [96, 72], "spp": 32, "max_depth": 8, "pixel_type": "float", "aovs": "albedo,normal,depth"%s}\n' \
    "$SRC/scenes/cornell-box/cornell-box.gltf" "$2" "${3:-}" >"$1"
}
job_file job.json out.exr ', "preview": "out.png"'
"$PRISM" render job.json -o single.exr -q

fail() { echo "FAILED: $*"; exit 1; }
# Polls `prism farm status` until it stops saying "not finished" (9); prints its last report.
wait_for() {
  local plan=$1 code=9
  for _ in $(seq 1 600); do
    set +e
    "$PRISM" farm status "$plan" >status.txt 2>&1
    code=$?
    set -e
    [[ $code -ne 9 ]] && break
    sleep 0.5
  done
  cat status.txt
  return $code
}
same_image() {  # the farm's output against the single-process render, to float rounding
  "$PRISM" compare "$1" single.exr --metric maxabs --threshold 1e-5 >compare.txt || { cat compare.txt; fail "$1 differs from single.exr"; }
  grep -q "prism/assembly.*Slurm merge job" <(exrheader "$1") || fail "$1: no prism/assembly naming the Slurm merge job"
  echo "$1 equals single.exr ($(tail -n 1 compare.txt))"
}

echo "== 1: by samples, 4 array tasks + merge"
"$PRISM" farm plan job.json --by samples --parts 4 --plan samples.farm --cpus-per-task 1 -q
"$PRISM" farm submit samples.farm
code=0; wait_for samples.farm || code=$?
[[ $code -eq 0 ]] || fail "farm status exited $code, expected 0"
same_image out.exr
[[ -s out.png ]] || fail "the merge wrote no preview out.png"
"$PRISM" farm submit samples.farm | tee submit.txt
grep -q "nothing to submit" submit.txt || fail "a complete plan was submitted again"

echo "== 2: by tiles, 4 array tasks + merge"
job_file tiles.json tiles.exr
"$PRISM" farm plan tiles.json --by tiles --parts 4 --plan tiles.farm --cpus-per-task 1 -q
"$PRISM" farm submit tiles.farm
code=0; wait_for tiles.farm || code=$?
[[ $code -eq 0 ]] || fail "farm status exited $code, expected 0"
same_image tiles.exr

echo "== 3: task 2 fails; the merge must never run"
job_file fail.json fail.exr
"$PRISM" farm plan fail.json --by samples --parts 4 --plan fail.farm --cpus-per-task 1 -q
mkdir fail.farm/parts/part002.exr  # a directory where task 2 writes its part: it exits 4
"$PRISM" farm submit fail.farm
code=0; wait_for fail.farm || code=$?
[[ $code -eq 8 ]] || fail "farm status exited $code, expected 8 (a task failed)"
grep -Eq "^ +2 +FAILED exit 4:0 +missing" status.txt || fail "status does not report task 2 FAILED with exit 4"
grep -q "part002.exr: output path is a directory" status.txt || fail "status does not give task 2's error"
# Slurm evaluates dependencies asynchronously: the merge is cancelled within a few seconds.
for _ in $(seq 1 120); do
  grep -Eq "^merge job [0-9]+: CANCELLED \(DependencyNeverSatisfied\)" status.txt && break
  sleep 0.25
  "$PRISM" farm status fail.farm >status.txt 2>&1 || true
done
cat status.txt
grep -Eq "^merge job [0-9]+: CANCELLED \(DependencyNeverSatisfied\)" status.txt || fail "the merge job was not cancelled"
[[ ! -e fail.exr ]] || fail "fail.exr exists: the merge ran although a task failed"
[[ $(grep -c "complete  " status.txt) -ge 3 ]] || fail "the other three tasks did not complete"
echo "task 2 failed, the merge was cancelled, fail.exr not written"

echo "== 3b: fixed and submitted again: only task 2 runs"
rmdir fail.farm/parts/part002.exr
"$PRISM" farm submit fail.farm | tee submit.txt
grep -q "submitted 1 of 4 tasks (2) as array job [0-9]* (the other 3 are complete)" submit.txt || fail "the resubmission did not run task 2 alone"
code=0; wait_for fail.farm || code=$?
[[ $code -eq 0 ]] || fail "farm status exited $code after the retry, expected 0"
"$PRISM" compare fail.exr single.exr --metric maxabs --threshold 1e-5 -q || fail "fail.exr differs from single.exr after the retry"
echo "retried: fail.exr equals single.exr"
echo "all farm cases passed"
