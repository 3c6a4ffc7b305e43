#!/usr/bin/env bash
# Issue 29: `robodds sweep --emit slurm` run by a real Slurm cluster. A one-node cluster on this
# machine (munged, slurmctld and slurmd from Debian's packages as children of this test, their
# files under the test's folder, on 127.0.0.1, ports from the test's domain) runs the emitted
# batch script of plant_smoke over seeds 1-8 (2 s each). Array task 3 fails once, as a lost node
# would: `robodds sweep --aggregate` names run 3 and the array index to resubmit; after
# `sbatch --array=3` the aggregate tables equal those of a local `--jobs 2` sweep of the same plan
# (summary.csv byte for byte; runs.csv but for the wall times). Exits 77 (skipped) with the reason
# where Slurm is not installed (scripts/setup.sh installs it).
source "$(dirname "$0")/lib.sh"
for tool in munged slurmctld slurmd sbatch squeue; do
  command -v "$tool" >/dev/null || { echo "skipped: $tool not found (Debian: slurmctld slurmd slurm-client munge, scripts/setup.sh)"; exit 77; }
done
[[ $(id -u) -eq 0 ]] || { echo "skipped: the one-node cluster's daemons run as root here"; exit 77; }
C="$WORK/cluster"
mkdir -p "$C/state" "$C/spool" "$C/munge" "$C/bin"
chmod 700 "$C/munge"
head -c 1024 /dev/urandom >"$C/munge/munge.key"
chmod 400 "$C/munge/munge.key"
munged -F --force --key-file="$C/munge/munge.key" --socket="$C/munge/socket" --pid-file="$C/munge/pid" \
  --seed-file="$C/munge/seed" --log-file="$C/munge/log" >"$C/munged.out" 2>&1 &
cleanup_pids+=("$!")
host=$(hostname -s)
port=$((16000 + 2 * DOMAIN))
cat >"$C/slurm.conf" <<CONF
ClusterName=robodds-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$C/munge/socket
CredType=cred/munge
StateSaveLocation=$C/state
SlurmdSpoolDir=$C/spool
SlurmctldPidFile=$C/slurmctld.pid
SlurmdPidFile=$C/slurmd.pid
SlurmctldLogFile=$C/slurmctld.log
SlurmdLogFile=$C/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 RealMemory=2000 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$C/slurm.conf"
for _ in $(seq 50); do [[ -S "$C/munge/socket" ]] && break; sleep 0.1; done
[[ -S "$C/munge/socket" ]] || fail "munged did not start: $(cat "$C/munged.out" "$C/munge/log" 2>/dev/null | tail -3)"
slurmctld -D -f "$SLURM_CONF" >"$C/slurmctld.out" 2>&1 &
cleanup_pids+=("$!")
slurmd -D -f "$SLURM_CONF" >"$C/slurmd.out" 2>&1 &
cleanup_pids+=("$!")
slurm_cleanup() {  # jobs first, then the daemons (lib.sh's cleanup kills the pids above)
  scancel --quiet --user root >/dev/null 2>&1 || true
  cleanup
}
trap slurm_cleanup EXIT
up=0
for _ in $(seq 100); do
  if sinfo -h -o '%T' 2>/dev/null | grep -q idle; then up=1; break; fi
  sleep 0.2
done
[[ $up -eq 1 ]] || fail "the one-node cluster did not come up: $(tail -3 "$C/slurmctld.log" "$C/slurmd.log" 2>/dev/null)"
echo "ok: one-node Slurm cluster up ($(sinfo -h -o '%P %D %c %T' | head -1))"

# The sweep: planned, emitted, run by Slurm; task 3 fails once before doing anything.
S="$SRC/sim/scenarios/plant_smoke.yaml"
"$ROBODDS" sweep "$S" --seeds 1-8 --duration 2 --out "$WORK/slurm" --plan >/dev/null || fail "--plan failed"
"$ROBODDS" sweep --emit slurm --out "$WORK/slurm" --domain-offset "$DOMAIN" >/dev/null || fail "--emit slurm failed"
cat >"$C/bin/robodds" <<WRAP
#!/bin/bash
if [[ \${SLURM_ARRAY_TASK_ID:-} == 3 && ! -e "$C/task3_failed" ]]; then
  touch "$C/task3_failed"; echo "simulated: the node of task 3 went away" >&2; exit 1
fi
exec "$ROBODDS" "\$@"
WRAP
chmod +x "$C/bin/robodds"
wait_job() {  # wait_job JOBID: until it left the queue (at most 180 s)
  for _ in $(seq 900); do
    [[ -z $(squeue -h -j "$1" 2>/dev/null) ]] && return 0
    sleep 0.2
  done
  fail "Slurm job $1 still queued after 180 s: $(squeue -h 2>&1 | head -3)"
}
job=$(ROBODDS="$C/bin/robodds" sbatch --parsable "$WORK/slurm/slurm.sbatch") || fail "sbatch refused the emitted script"
wait_job "$job"
"$ROBODDS" sweep --aggregate --out "$WORK/slurm" >"$WORK/aggregate1.log" 2>&1 || fail "--aggregate failed: $(tail -3 "$WORK/aggregate1.log")"
grep -q "sweep: run 3 (seed 4) has no result in $WORK/slurm/runs/0003: run it with robodds sweep --run-index 3 --out $WORK/slurm" "$WORK/aggregate1.log" ||
  fail "the lost task is not named: $(tail -4 "$WORK/aggregate1.log")"
grep -q "sbatch --array=3 " "$WORK/aggregate1.log" || fail "no array index to resubmit: $(tail -3 "$WORK/aggregate1.log")"
grep -q "(8 runs, 0 failed, 1 not run)" "$WORK/aggregate1.log" || fail "expected 7 of 8 runs: $(tail -2 "$WORK/aggregate1.log")"
echo "ok: Slurm ran 7 of 8 array tasks (task 3 lost); --aggregate names run 3 and its array index"
job=$(ROBODDS="$C/bin/robodds" sbatch --parsable --array=3 "$WORK/slurm/slurm.sbatch") || fail "resubmitting task 3 failed"
wait_job "$job"
"$ROBODDS" sweep --aggregate --out "$WORK/slurm" >"$WORK/aggregate2.log" 2>&1 || fail "--aggregate failed: $(tail -3 "$WORK/aggregate2.log")"
grep -q "(8 runs, 0 failed)" "$WORK/aggregate2.log" || fail "not every run ok after the resubmission: $(tail -2 "$WORK/aggregate2.log")"

# The same plan on this machine, two runs at a time.
"$ROBODDS" --log warn sweep "$S" --seeds 1-8 --duration 2 --jobs 2 --domain "$DOMAIN" --out "$WORK/local" >"$WORK/local.log" 2>&1 ||
  fail "the local sweep failed: $(tail -3 "$WORK/local.log")"
cmp "$WORK/slurm/summary.csv" "$WORK/local/summary.csv" || fail "summary.csv differs between Slurm and the local sweep"
python3 - "$WORK/slurm/runs.csv" "$WORK/local/runs.csv" <<'PY' || fail "runs.csv differs beyond the wall times"
import csv, sys
def rows(path):
    table = list(csv.reader(open(path)))
    wall = table[0].index("wall_s")
    return [r[:wall] + r[wall + 1:] for r in table]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
sys.exit(0 if a == b and len(a) == 9 else f"runs.csv: {len(a) - 1} and {len(b) - 1} runs, first difference: "
         + next((f"{x} / {y}" for x, y in zip(a, b) if x != y), "none"))
PY
echo "ok: after resubmitting task 3 the Slurm sweep's tables equal the local --jobs 2 sweep's (summary.csv byte for byte, runs.csv but wall_s)"
