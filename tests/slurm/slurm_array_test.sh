#!/usr/bin/env bash
# A sweep run as a real Slurm job array on a single-node cluster started here
# (slurmctld + slurmd on this host, munge for authentication, everything under
# a temporary directory, driven through SLURM_CONF): 4 array tasks each run
# their shard into their own database, a dependent job merges them, and the
# merged report must equal the report of the same sweep run unsharded.
# Needs root (the daemons run as root) and Debian's slurm-wlm and munge
# (scripts/install-deps). Exits 77 (ctest: skipped) with the reason only when
# the daemons cannot be started here; stops every daemon and job it started,
# on every exit: a watchdog ends it (TERM, so the cleanup runs) 30 s before
# ctest's 400 s timeout would kill it. The node is addressed as 127.0.0.1 by
# a fixed name, so the machine's host name need not resolve. Every wait is
# bounded and says what it waited for.
# Usage: slurm_array_test.sh RRLAB_BINARY SPEC.json
set -euo pipefail
rrlab=$(readlink -f "$1")
spec=$(readlink -f "$2")
skip() { echo "SKIPPED: $*"; exit 77; }

[[ $(id -u) -eq 0 ]] || skip "the single-node cluster needs root"
for tool in slurmctld slurmd sbatch squeue sinfo munged munge; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (scripts/install-deps installs slurm-wlm and munge)"
done

work=$(mktemp -d /tmp/rrlab-slurm.XXXXXX)
chmod 755 "$work"
node=rrlab-node  # slurmd -N: the node's name; its address is 127.0.0.1
export SLURM_CONF="$work/slurm.conf"
jobs=""
cleanup() {
  local status=$?
  # the cleanup must not fail (set -e) nor be cut short: stopping the
  # watchdog's sleep wakes the watchdog, which may still send its TERM
  set +e
  trap - EXIT
  trap '' INT TERM
  if [[ -n ${watchdog:-} ]]; then pkill -P "$watchdog" 2>/dev/null; kill "$watchdog" 2>/dev/null; fi
  [[ -n $jobs ]] && scancel $jobs 2>/dev/null
  for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munged.pid"; do
    [[ -s $pidfile ]] && kill "$(cat "$pidfile")" 2>/dev/null
  done
  # up to 10 s for them to go, then SIGKILL
  for _ in $(seq 1 100); do
    alive=0
    for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munged.pid"; do
      [[ -s $pidfile ]] && kill -0 "$(cat "$pidfile")" 2>/dev/null && alive=1
    done
    ((alive)) || break
    sleep 0.1
  done
  for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munged.pid"; do
    [[ -s $pidfile ]] && kill -9 "$(cat "$pidfile")" 2>/dev/null
  done
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
trap 'echo "FAILED: stopped by a signal (the watchdog: 370 s)"; exit 1' INT TERM
# ctest's TIMEOUT is 400 s and its kill leaves no chance to clean up: end first
(sleep 370 & wait $!; kill -TERM $$ 2>/dev/null) >/dev/null 2>&1 &
watchdog=$!

# munge: its own key, socket and pid file in the work directory
mkdir -p "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munge/log" --seed-file="$work/munge/seed" 2>"$work/munged.err" \
  || skip "munged did not start: $(tail -1 "$work/munged.err")"
export MUNGE_SOCKET="$work/munge/socket"  # read by munge/unmunge; slurm reads AuthInfo below
munge -n --socket="$work/munge/socket" | unmunge --socket="$work/munge/socket" >/dev/null || skip "munge does not authenticate here"

mkdir -p "$work/state" "$work/spool" "$work/log"
cat > "$SLURM_CONF" <<CONF
ClusterName=rrlab-test
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmctldPort=$((20000 + RANDOM % 20000))
SlurmdPort=$((40000 + RANDOM % 20000))
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -c || skip "slurmctld did not start: $(tail -3 "$work/log/slurmctld.log" 2>/dev/null)"
slurmd -N "$node" || skip "slurmd did not start: $(tail -3 "$work/log/slurmd.log" 2>/dev/null)"
for _ in $(seq 1 60); do
  sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)' && break
  sleep 0.5
done
sinfo -h -o %T | grep -qE '^(idle|mixed|allocated)' ||
  skip "the node did not come up within 30 s: $(sinfo 2>&1 | tail -2); slurmd: $(tail -2 "$work/log/slurmd.log" 2>/dev/null)"

# the job array and the merge that waits for it, as deploy/slurm does
out="$work/out"
mkdir -p "$out"
array=$(sbatch --parsable --array=0-3 --output="$out/task-%a.log" --chdir="$out" \
  --export=ALL,RRLAB="$rrlab",SPEC="$spec",OUT="$out" \
  --wrap='"$RRLAB" sweep "$SPEC" --db "$OUT/shard-$SLURM_ARRAY_TASK_ID.db" --jobs 1')
jobs="$array"
merge=$(sbatch --parsable --dependency=afterok:"$array" --kill-on-invalid-dep=yes --output="$out/merge.log" --chdir="$out" \
  --export=ALL,RRLAB="$rrlab",OUT="$out" \
  --wrap='"$RRLAB" merge "$OUT/merged.db" "$OUT"/shard-*.db')
jobs="$array $merge"
echo "slurm: array job $array (4 tasks), merge job $merge"
# until squeue (which must answer) lists none of them; 240 s at most
for _ in $(seq 1 480); do
  listed=$(squeue -h -j "$array,$merge" -o '%i %T' 2>&1) || { echo "FAILED: squeue failed: $listed"; exit 1; }
  [[ -z $listed ]] && break
  sleep 0.5
done
[[ -z $listed ]] || { echo "FAILED: the jobs did not end within 240 s:"; echo "$listed"; tail -5 "$work/log/slurmctld.log"; exit 1; }
jobs=""
for i in 0 1 2 3; do
  [[ -s $out/shard-$i.db ]] || { echo "FAILED: task $i wrote no database"; cat "$out/task-$i.log" 2>/dev/null; exit 1; }
done
[[ -s $out/merged.db ]] || { echo "FAILED: the merge job wrote nothing"; cat "$out/merge.log" 2>/dev/null; exit 1; }

# the same sweep unsharded, then both reports (without step times, which are not deterministic)
"$rrlab" sweep "$spec" --db "$work/whole.db" --jobs 2 >/dev/null 2>&1
"$rrlab" report "$out/merged.db" --format csv --out "$work/merged.csv"
"$rrlab" report "$work/whole.db" --format csv --out "$work/whole.csv"
strip() { python3 -c 'import csv,sys
rows=list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    print({k:v for k,v in r.items() if "step" not in k})' "$1"; }
if diff <(strip "$work/merged.csv") <(strip "$work/whole.csv"); then
  echo "slurm array test: the merged report of 4 array tasks equals the unsharded one"
  echo "1 passed, 0 failed"
else
  echo "FAILED: merged and unsharded reports differ"
  exit 1
fi
