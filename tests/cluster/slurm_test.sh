#!/usr/bin/env bash
# app/cluster/slurm-array.sh on a real one-node Slurm (Debian's slurm-wlm and munge): munged with
# a fresh key, slurmctld and slurmd with a configuration in a temporary folder (no cgroups), the
# node given 2 CPUs whatever the machine has (a recipe asking more would wait for ever). Submits
# docs/cluster.md's command as written, an array of 3 tasks over a grid of 4 blends, and checks that
# every output exists exactly once, that the tasks' summaries cover every job exactly once and
# that each task ran one job at a time; then one task with --cpus-per-task=2 on the submit line,
# which runs batch with --jobs 2. Stops the daemons by their process ids and removes the folder
# however it ends. Needs root (the daemons); says "skipped: ..." and
# exits 0 otherwise.
#   tests/cluster/slurm_test.sh [MOSTYLE_CLI]     (default: build/app/mostyle-cli)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
if [ "$(id -u)" -ne 0 ]; then
  echo "skipped: the Slurm test starts munged, slurmctld and slurmd, which needs root"
  exit 0
fi
cli="$(realpath "${1:-${MOSTYLE_CLI:-$root/build/app/mostyle-cli}}")"
[ -x "$cli" ] || { echo "slurm test: no mostyle-cli at $cli (build it first)"; exit 1; }
for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" >/dev/null || { echo "slurm test: $tool is missing (app/install-deps.sh installs slurm-wlm and munge)"; exit 1; }
done

tmp="$(mktemp -d /tmp/mostyle_slurm.XXXXXX)"
pids=()
cleanup() {
  local status=$?
  # Our own daemons only, by the ids we started them with: TERM, then KILL after 10 s.
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  if [ "$status" -ne 0 ]; then
    for log in "$tmp"/*.log "$tmp"/work/logs/*.out; do
      [ -f "$log" ] && { echo "--- $log"; tail -n 30 "$log"; }
    done
  fi
  rm -rf "$tmp"
  exit "$status"
}
trap cleanup EXIT
fail() { echo "slurm test: $*"; exit 1; }

# munge: a fresh key and its own socket, pid, log and seed files.
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/work/logs"
chmod 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key"
socket="$tmp/munge/munge.socket"
munged --foreground --force --socket="$socket" --key-file="$tmp/munge/munge.key" \
    --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munge/munged.seed" 2>>"$tmp/munged.log" &
pids+=($!)

# Slurm: this host as the one node with 2 CPUs, as small as a node gets (config_overrides: a
# larger machine registers as configured), its memory as slurmd -C reads it; ports of our own so
# that another Slurm on the machine is left alone.
host="$(hostname -s)"
memory="$(slurmd -C | head -n 1 | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')"
node="NodeName=$host CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=${memory:-1024}"
port=$((20000 + RANDOM % 20000))
cat >"$tmp/slurm.conf" <<CONF
ClusterName=mostyle-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=10 State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || fail "munged did not start"
slurmctld -D -i -f "$SLURM_CONF" 2>>"$tmp/slurmctld.log" &
pids+=($!)
slurmd -D -f "$SLURM_CONF" 2>>"$tmp/slurmd.log" &
pids+=($!)
for _ in $(seq 150); do
  state="$(sinfo -h -n "$host" -o %t 2>/dev/null || true)"
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || fail "the node is not idle after 30 s (state: '${state:-none}')"

# The grid: 2 takes x 2 alphas = 4 blends, run by an array of 3 tasks (shard 0/3 has 2 jobs).
cd "$tmp/work"
cp "$root/assets/motions/cmu142_walk_happy.bvh" "$root/assets/motions/cmu142_walk_joy.bvh" .
"$cli" grid --takes cmu142_walk_happy.bvh cmu142_walk_joy.bvh --alphas 0,1 --out-dir out --jobs-out jobs.jsonl \
    -- --components 4 --iterations 20
[ "$(wc -l <jobs.jsonl)" -eq 4 ] || fail "expected 4 jobs, found $(wc -l <jobs.jsonl)"
# mostyle-cli behind a wrapper that writes down the arguments each task ran batch with.
cat >"$tmp/cli-args.sh" <<WRAP
#!/bin/sh
echo "\$@" >"$tmp/work/logs/args_\$SLURM_ARRAY_TASK_ID"
exec "$cli" "\$@"
WRAP
chmod +x "$tmp/cli-args.sh"
export MOSTYLE_CLI="$tmp/cli-args.sh"

# Waits for array $1 to leave the queue (120 s at most); a task that cannot run on this node
# fails at once, naming squeue's reason.
wait_for_array() {
  local reason
  for _ in $(seq 600); do
    [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
    reason="$(squeue -h -j "$1" -o %r 2>/dev/null | sort -u | tr '\n' ' ')"
    case "$reason" in
      *PartitionConfig*)
        fail "array $1 cannot run on a node of 2 CPUs (squeue's reason: $reason)" ;;
    esac
    sleep 0.2
  done
  fail "the array $1 has not finished after 120 s"
}

# docs/cluster.md's command as written (--parsable only to read the array's id).
job="$(sbatch --parsable --array=0-2 "$root/app/cluster/slurm-array.sh" jobs.jsonl)" ||
  fail "sbatch refused docs/cluster.md's command on a node of 2 CPUs"
echo "slurm test: submitted array $job"
wait_for_array "$job"

# Every output exactly once: the folder holds the 8 files of the 4 jobs and nothing else.
expected="$(sed 's/.*"--out","\([^"]*\)","--report","\([^"]*\)".*/\1\n\2/' jobs.jsonl | sort)"
found="$(find out -type f | sort)"
[ "$found" = "$expected" ] || fail "outputs: expected
$expected
found
$found"
# The summaries together: every line of jobs.jsonl exactly once, each ok.
for t in 0 1 2; do [ -f "logs/summary_$t.json" ] || fail "task $t wrote no summary"; done
lines="$(cat logs/summary_*.json | grep -o '"line": [0-9]*' | sort -t: -k2 -n | tr -d ' ' | tr '\n' ' ')"
[ "$lines" = '"line":1 "line":2 "line":3 "line":4 ' ] || fail "summaries cover lines: $lines"
ok="$(cat logs/summary_*.json | grep -c '"status": "ok"')"
[ "$ok" -eq 4 ] || fail "expected 4 ok jobs in the summaries, found $ok"
for t in 0 1 2; do
  grep -q -- "--jobs 1 " "logs/args_$t" || fail "task $t ran: $(cat "logs/args_$t"), expected --jobs 1"
done
echo "slurm test: array $job of 3 tasks ran 4 blends, every output once, summaries cover every job once"

# N CPUs from the submit line: batch runs N jobs at once (every output is there: all skipped).
rm -f logs/args_*
job="$(sbatch --parsable --array=0-0 --cpus-per-task=2 "$root/app/cluster/slurm-array.sh" jobs.jsonl)" ||
  fail "sbatch refused --cpus-per-task=2 on a node of 2 CPUs"
wait_for_array "$job"
grep -q -- "--jobs 2 " logs/args_0 || fail "with --cpus-per-task=2 the task ran: $(cat logs/args_0 2>/dev/null)"
echo "slurm test: --cpus-per-task=2 on the submit line ran batch with --jobs 2"
