#!/usr/bin/env bash
# docs/scale_out.md's Slurm recipe on a one-node Slurm cluster of the test's own (munged,
# slurmctld and slurmd on 127.0.0.1, their configuration, state and logs in a temporary folder;
# nothing of the machine's /etc is used): the documented array job over 16 shards of 320 images,
# one task cancelled mid-run with scancel (SIGTERM, as a time limit sends), that task resubmitted
# alone as the recipe says, the shards merged as it says; the merged file must equal one
# `aief extract --batch` process in every group, dataset and attribute (h5dump of both).
#   tests/slurm/array_recipe.sh BUILD_DIR
# Exits 77 (CTest: skipped) saying why where it cannot run: Slurm, munge or h5dump not installed
# (scripts/ci_slurm installs them), or not root (slurmd starts the tasks as their user).
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build_dir=$(cd "$1" && pwd)
skip() { echo "skipped: $*"; exit 77; }
fail() { echo "slurm recipe test: $*" >&2; exit 1; }
for program in munged slurmctld slurmd sbatch scancel squeue sinfo scontrol h5dump; do
  command -v "$program" > /dev/null ||
    skip "$program is not installed (apt-get install munge slurmctld slurmd slurm-client hdf5-tools; scripts/ci_slurm does)"
done
[ "$(id -u)" -eq 0 ] || skip "slurmd runs as root to start the tasks as their user (CI runs as root)"
[ -x "$build_dir/aief" ] || fail "no aief tool in $build_dir"

work=$(mktemp -d)
chmod 700 "$work"  # munged refuses a socket or key in a folder others can write
daemons=()
cleanup() {
  local status=$?
  if [ -e "$work/slurm.conf" ] && ((${#daemons[@]})); then
    SLURM_CONF=$work/slurm.conf scancel --partition=aief 2> /dev/null || true
    SLURM_CONF=$work/slurm.conf scontrol shutdown 2> /dev/null || true
    sleep 2
  fi
  local pid
  for pid in "${daemons[@]}"; do kill "$pid" 2> /dev/null || true; done
  for pid in "${daemons[@]}"; do wait "$pid" 2> /dev/null || true; done
  if ((status != 0 && status != 77)); then
    for log in slurmctld slurmd; do [ -e "$work/$log.log" ] && { echo "--- $log.log (tail)"; tail -n 20 "$work/$log.log"; }; done
    for out in "$work"/job/slurm-*.out; do [ -e "$out" ] && { echo "--- $(basename "$out")"; cat "$out"; }; done
  fi
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 143' TERM INT

# munge: a key and a socket of its own.
mkdir -m 700 "$work/munge"
head -c 1024 /dev/urandom > "$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed" \
  > "$work/munge/munged.out" 2>&1 &
daemons+=($!)

# Two free ports on the loopback for slurmctld and slurmd.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks: s.bind(("127.0.0.1", 0))
print(*[s.getsockname()[1] for s in socks])')
host=$(hostname -s)
node=aiefnode
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool" "$work/job"
cat > "$work/slurm.conf" <<CONF
ClusterName=aief
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
PlugStackConfig=$work/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=3600
KillWait=30
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus State=UNKNOWN
PartitionName=aief Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
: > "$work/plugstack.conf"
export SLURM_CONF=$work/slurm.conf
for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.2; done
[ -S "$work/munge/munge.socket" ] || { cat "$work/munge/munged.out"; fail "munged did not start"; }
slurmctld -D -c -f "$SLURM_CONF" > "$work/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" > "$work/slurmd.out" 2>&1 &
daemons+=($!)
state=""
for _ in $(seq 150); do
  state=$(sinfo -h -n "$node" -o %T 2> /dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || { cat "$work/slurmctld.out" "$work/slurmd.out"; fail "the one-node cluster did not come up (node state '$state')"; }

# The recipe, as docs/scale_out.md writes it: its first sh block after "## Slurm".
awk '/^## Slurm/ {s = 1} s && /^```sh/ {b = 1; next} b && /^```/ {exit} b' "$source_dir/docs/scale_out.md" > "$work/job/extract.sbatch"
grep -q '^#SBATCH --array=0-15' "$work/job/extract.sbatch" || fail "no 16-task array recipe found in docs/scale_out.md"
mkdir -p "$work/job/build" "$work/job/images"
ln -s "$build_dir/aief" "$work/job/build/aief"
i=0
for round in $(seq 54); do
  for image in "$source_dir"/data/samples/{graf,boat,leuven}/img{1,2}.png; do
    ((i < 320)) || break 2
    cp "$image" "$work/job/images/$(printf 'i%03d' $i).png"
    i=$((i + 1))
  done
done
cd "$work/job"

# task_states JOB: "task state exit" per line, from scontrol (no accounting database here).
task_states() {
  scontrol -o show job "$1" | sed -nE 's/.*ArrayTaskId=([0-9]+) .*JobState=([A-Z_]+) .*ExitCode=([0-9:]+).*/\1 \2 \3/p'
}
wait_for_job() {  # wait_for_job JOB: until none of its tasks is pending or running (10 minutes at most)
  local waited=0
  while [ -n "$(squeue -h -j "$1" -o %i 2> /dev/null)" ]; do
    ((waited < 3000)) || fail "job $1 still running after 10 minutes"
    sleep 0.2
    waited=$((waited + 1))
  done
}

# 16 tasks of one CPU each (the recipe asks 8, this node has $cpus): sbatch's options override #SBATCH.
job=$(sbatch --parsable --cpus-per-task=1 -o "slurm-%A_%a.out" extract.sbatch)
# Mid-run: once the task's own progress line says an image is done (its shard has 20).
cancelled=15
progress=""
for _ in $(seq 6000); do
  progress=$(grep -m 1 -E '^batch: [1-9][0-9]*/' "slurm-${job}_$cancelled.out" 2> /dev/null || true)
  [ -n "$progress" ] && break
  sleep 0.1
done
[ -n "$progress" ] || fail "task $cancelled showed no progress within 10 minutes"
scancel "${job}_$cancelled"
wait_for_job "$job"
states=$(task_states "$job")
echo "$states" | awk -v c="$cancelled" '$1 != c && !($2 == "COMPLETED" && $3 == "0:0") {bad = 1} END {exit bad}' ||
  fail "a task other than $cancelled did not complete: $states"
echo "$states" | grep -q "^$cancelled CANCELLED " ||
  fail "task $cancelled was not cancelled mid-run (it finished before scancel reached it?): $states"
echo "array job $job: 15 tasks completed, task $cancelled cancelled by scancel (SIGTERM) after '$progress'"

# Resubmitted alone, as docs/scale_out.md says.
resubmit=$(sed -nE 's/.*`(sbatch --array=[0-9]+ extract\.sbatch)`.*/\1/p' "$source_dir/docs/scale_out.md" | head -n 1)
[ -n "$resubmit" ] || fail "docs/scale_out.md names no resubmission command (sbatch --array=N extract.sbatch)"
rejob=$(sbatch --parsable --cpus-per-task=1 -o "slurm-%A_%a.out" --array=$cancelled extract.sbatch)
wait_for_job "$rejob"
restate=$(task_states "$rejob")
grep -q "^$cancelled COMPLETED 0:0" <<< "$restate" || fail "the resubmitted task $cancelled did not complete: $restate"
echo "task $cancelled resubmitted alone ($resubmit with $cancelled): completed, $(grep -h 'images in this shard' "slurm-${rejob}_$cancelled.out" || true)"

merge=$(sed -nE 's/.*`(build\/aief merge [^`]*)`.*/\1/p' "$source_dir/docs/scale_out.md" | head -n 1)
[ -n "$merge" ] || fail "docs/scale_out.md names no merge command"
$merge > merge.out 2>&1 || { cat merge.out; fail "$merge failed"; }
# One process with the tasks' options (--threads 1 too: the option record keeps the thread count).
build/aief extract --batch images -o single.h5 --format h5 --threads 1 > single.out 2>&1 || { cat single.out; fail "the single-process extraction failed"; }
h5dump features.h5 | tail -n +2 > merged.dump
h5dump single.h5 | tail -n +2 > single.dump
groups=$(grep -c 'GROUP "i[0-9]*.png"' single.dump || true)
[ "$groups" -eq 320 ] || fail "the single-process file has $groups image groups, not 320"
diff -q merged.dump single.dump > /dev/null || { diff merged.dump single.dump | head -n 20; fail "the merged shards differ from one process"; }
echo "merged ($merge): 320 images, every group, dataset and attribute equal to one aief extract --batch process"
