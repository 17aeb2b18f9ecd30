#!/usr/bin/env bash
# A real Slurm scheduler on this machine: munged with its own key and socket, slurmctld and
# slurmd on 127.0.0.1 from a generated slurm.conf, all state in a temporary folder. Submits a
# small sweep through `contactlab run --slurm`, waits, and checks that the merged results equal
# a local run of the same config (every column but the timings, *_us); then submits a sweep
# with one failing task and checks that the merge fails naming it and merges nothing.
# Everything is stopped and removed at the end, also on failure or timeout.
#
#   single_node_cluster_test.sh CONTACTLAB_BINARY
# Exit status: 0 passed, 1 failed, 77 skipped (not root, or Slurm/munge missing or unable to
# start here; the reason is printed). Needs Debian's slurm-wlm and munge (install-deps.sh).
set -uo pipefail
contactlab=${1:?usage: single_node_cluster_test.sh CONTACTLAB_BINARY}
limit=${CONTACTLAB_SLURM_TEST_TIMEOUT:-100}   # seconds for the whole test
start=$(date +%s)

# The whole test runs under timeout(1): on expiry the TERM trap below stops everything.
if [ -z "${CONTACTLAB_SLURM_TEST_TIMED:-}" ]; then
  export CONTACTLAB_SLURM_TEST_TIMED=1
  exec timeout --kill-after=15 "$limit" bash "$0" "$@"
fi

skip() { echo "SKIPPED: $*" >&2; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || skip "a private slurmctld/slurmd/munged needs root here (running as uid $(id -u))"
for tool in munged munge slurmctld slurmd sbatch squeue scontrol python3; do
  command -v "$tool" >/dev/null 2>&1 || skip "$tool is not installed (./scripts/install-deps.sh installs slurm-wlm and munge)"
done
[ -x "$contactlab" ] || fail "no program $contactlab"
contactlab=$(readlink -f "$contactlab")

tmp=$(mktemp -d /tmp/contactlab-slurm.XXXXXX)
chmod 711 "$tmp"   # munged requires its socket's folder to be searchable by all
pids=()
cleanup() {
  local status=$?
  trap - EXIT TERM INT
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then scancel --quiet --user=root 2>/dev/null; fi
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive -eq 0 ] && break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; done
  if [ $status -ne 0 ] && [ $status -ne 77 ]; then
    for log in slurmctld.log slurmd.log munged.log; do
      [ -f "$tmp/$log" ] && { echo "--- $log (last lines)"; tail -n 15 "$tmp/$log"; } >&2
    done
  fi
  rm -rf "$tmp"
  echo "slurm test: $(( $(date +%s) - start )) s" >&2
  exit $status
}
trap cleanup EXIT
trap 'echo "FAILED: timed out after ${limit} s" >&2; exit 1' TERM
trap 'exit 1' INT

# Waits up to $1 seconds for the command "${@:2}" to succeed.
wait_for() {
  local seconds=$1; shift
  local until=$(( $(date +%s) + seconds ))
  while ! "$@" >/dev/null 2>&1; do
    [ "$(date +%s)" -ge "$until" ] && return 1
    sleep 0.2
  done
}

# --- munge: its own key, socket, pid and log in $tmp
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge.key"
munged --foreground --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" >"$tmp/munged.out" 2>&1 &
pids+=($!)
wait_for 10 munge -S "$tmp/munge.socket" -n ||
  skip "munged did not start: $(tail -n 3 "$tmp/munged.log" "$tmp/munged.out" 2>/dev/null | tr '\n' ' ')"

# --- slurm.conf: controller and node on 127.0.0.1, two free ports, no cgroups, no accounting
read -r ctld_port node_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
mkdir -p "$tmp/state" "$tmp/spool"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=contactlab-test
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MinJobAge=600
NodeName=contactlab-node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=contactlab-node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N contactlab-node -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
node_idle() { [ "$(sinfo -h -n contactlab-node -o %t 2>/dev/null)" = idle ]; }
wait_for 30 node_idle ||
  skip "slurmctld/slurmd did not bring the node up: $(tail -n 3 "$tmp/slurmctld.log" "$tmp/slurmd.log" "$tmp/slurmctld.out" "$tmp/slurmd.out" 2>/dev/null | tr '\n' ' ')"
echo "slurm test: scheduler up after $(( $(date +%s) - start )) s" >&2

# --- a small sweep: three pointshell sizes, a ball pressed into a plate
cat > "$tmp/scene.yaml" <<'YAML'
name: slurm-ball-plate
bodies:
  - name: ball
    mesh: "sphere:0.02,3"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 512, levels: 2}
    field: {resolution: 24}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 24}
model: {k_C: 1000}
YAML
sed -e 's/name: slurm-ball-plate/name: slurm-broken/' -e 's/"box:0.05,0.05,0.01,2"/no-such-mesh.obj/' \
  "$tmp/scene.yaml" > "$tmp/broken.yaml"
cat > "$tmp/sweep.yaml" <<'YAML'
name: slurm-sweep
scene: scene.yaml
trajectory: {type: approach-press, duration: 0.05}
sweep: {points: [64, 128, 256]}
YAML
cat > "$tmp/failing.yaml" <<'YAML'
name: slurm-failing
scene: scene.yaml
trajectory: {type: approach-press, duration: 0.05}
sweep: {scene: [scene.yaml, broken.yaml, scene.yaml]}
YAML
cache=(--cache "$tmp/cache")

"$contactlab" run "$tmp/sweep.yaml" --out "$tmp/local" "${cache[@]}" >"$tmp/local.txt" 2>&1 ||
  fail "local run: $(cat "$tmp/local.txt")"

# Submits CONFIG into OUT through `contactlab run --slurm`; sets array_job and merge_job.
submit() {
  local config=$1 out=$2
  "$contactlab" run "$config" --slurm --partition test --time 2 --out "$out" "${cache[@]}" >"$out.submit.txt" 2>&1 ||
    fail "contactlab run --slurm: $(cat "$out.submit.txt")"
  cat "$out.submit.txt"
  array_job=$(sed -n 's/^array_job=//p' "$out.submit.txt")
  merge_job=$(sed -n 's/^merge_job=//p' "$out.submit.txt")
  [ -n "$array_job" ] && [ -n "$merge_job" ] || fail "no job ids printed by contactlab run --slurm"
}
# Waits until JOB has left the queue; prints its final state.
final_state() {
  local job=$1
  queue_empty() { [ -z "$(squeue -h -j "$job" 2>/dev/null)" ]; }
  wait_for $(( limit - ($(date +%s) - start) )) queue_empty || { echo "still queued at the time limit"; return 0; }
  scontrol show job "$job" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1
}

# --- 1. the sweep: merged results equal the local run's, timings aside
submit "$tmp/sweep.yaml" "$tmp/cluster"
state=$(final_state "$merge_job")
[ "$state" = COMPLETED ] || fail "merge job $merge_job ended $state: $(cat "$tmp/cluster/slurm/merge.log" 2>/dev/null)"
for task in 0 1 2; do
  [ -f "$tmp/cluster/job-$task/summary.csv" ] || fail "task $task left no summary.csv"
done
python3 - "$tmp/local" "$tmp/cluster" <<'PY' || fail "merged results differ from the local run"
import csv, sys
local, cluster = sys.argv[1], sys.argv[2]
for name in ("summary.csv", "cycles.csv", "convergence.csv"):
    rows = []
    for folder in (local, cluster):
        with open(f"{folder}/{name}", newline="") as f:
            table = list(csv.reader(f))
        keep = [i for i, h in enumerate(table[0]) if not h.endswith("_us")]
        rows.append([[r[i] for i in keep] for r in table])
    if rows[0] != rows[1]:
        bad = next(i for i, (a, b) in enumerate(zip(rows[0], rows[1])) if a != b) if len(rows[0]) == len(rows[1]) else None
        print(f"{name}: local {len(rows[0])} rows, merged {len(rows[1])} rows; first difference at row {bad}",
              file=sys.stderr)
        sys.exit(1)
    print(f"{name}: {len(rows[0]) - 1} rows identical to the local run (timing columns aside)")
PY

# --- 2. a sweep whose task 1 fails: the merge fails, names task 1, and merges nothing
submit "$tmp/failing.yaml" "$tmp/failing"
state=$(final_state "$merge_job")
[ "$state" = FAILED ] || fail "merge job $merge_job after a failed task ended $state, not FAILED"
grep -q "task 1: $tmp/failing/job-1" "$tmp/failing/slurm/merge.log" ||
  fail "merge.log does not name task 1: $(cat "$tmp/failing/slurm/merge.log")"
grep -q "no-such-mesh.obj" "$tmp/failing/slurm/job-1.log" || fail "task 1's log does not say why it failed"
[ ! -e "$tmp/failing/summary.csv" ] || fail "a partial summary.csv was written"
echo "merge after a failed task: $(grep -m1 'sweep tasks' "$tmp/failing/slurm/merge.log")"
echo "PASSED"
