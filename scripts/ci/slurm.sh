#!/usr/bin/env bash
# CI job: a real single-node Slurm on localhost runs a small sweep as 4 shards plus the merge
# job through scripts/slurm-sweep.sh, and the merged CSV must equal an unsplit run's bytes.
# Installs nothing (scripts/install-deps.sh brings slurm-wlm and munge); needs root (munged
# and slurmd as root, no cgroups). Starts munged, slurmctld and slurmd on private ports with
# their state in a temporary directory and stops them on exit.
#
#   bash scripts/ci/slurm.sh [path/to/dampbound]     (default build/app/dampbound)
set -euo pipefail
cd "$(dirname "$0")/../.."

DB=${1:-build/app/dampbound}
fail() { echo "slurm CI: FAIL: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || fail "needs root (munged and slurmd run as root here)"
for tool in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$tool" >/dev/null || fail "$tool not found: run scripts/install-deps.sh"
done
[ -x "$DB" ] || fail "$DB not built"
DB=$(cd "$(dirname "$DB")" && pwd)/$(basename "$DB")

WORK=$(mktemp -d /tmp/dampbound-slurm.XXXXXX)
chmod 755 "$WORK"
HOST=$(hostname -s)
PORT=${DAMPBOUND_SLURM_PORT:-16817}
export SLURM_CONF=$WORK/slurm.conf
started=()
cleanup() {
  local code=$?
  for pidfile in "$WORK/slurmd.pid" "$WORK/slurmctld.pid" "$WORK/munged.pid"; do
    [ -s "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null || true
  done
  sleep 1
  if [ $code -ne 0 ]; then
    for log in slurmctld.log slurmd.log munged.log; do
      [ -f "$WORK/$log" ] && { echo "--- $log (last lines)"; tail -n 20 "$WORK/$log"; }
    done
  fi
  rm -rf "$WORK"
  exit $code
}
trap cleanup EXIT

# munge: its own key and socket, so nothing system-wide is touched.
mkdir -p "$WORK/munge" "$WORK/state" "$WORK/spool" "$WORK/run"
chmod 711 "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
munged --force --key-file="$WORK/munge/munge.key" --socket="$WORK/munge/munge.sock" \
  --pid-file="$WORK/munged.pid" --log-file="$WORK/munged.log" --seed-file="$WORK/munge/seed" \
  || fail "munged did not start"

cat > "$SLURM_CONF" <<EOF
ClusterName=dampbound-ci
SlurmctldHost=$HOST
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
AuthInfo=socket=$WORK/munge/munge.sock
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=ci Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 1 60); do
  sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)' && break
  sleep 1
done
sinfo -h -o '%T' | grep -qE '^(idle|mixed|allocated)' || fail "the node never came up: $(sinfo -h 2>&1)"
echo "slurm CI: single-node cluster up on $HOST ($(sinfo -h -o '%c CPUs, %T'))"

GRID=(--m 0.001:0.004:0.001 --kappa 0.001:0.004:0.001 --zeta 0.5,1 --max-iter 60 --threads 1)
"$DB" sweep "${GRID[@]}" -o "$WORK/whole.csv" --progress none >/dev/null \
  || fail "the unsplit sweep failed"
start=$(date +%s)
bash scripts/slurm-sweep.sh -n 4 -o "$WORK/out/merged.csv" --dampbound "$DB" --wait \
  -- "${GRID[@]}" || fail "the job array or its merge failed: $(cat "$WORK"/out/*.log 2>/dev/null)"
parts=$(ls "$WORK"/out/merged.csv.part*.csv | wc -l)
[ "$parts" -eq 4 ] || fail "$parts part files, wanted 4"
cmp -s "$WORK/whole.csv" "$WORK/out/merged.csv" || fail "merged CSV differs from the unsplit run"
echo "slurm CI: PASS: 4 shards + merge through Slurm ($(($(date +%s) - start)) s) give the unsplit sweep's $(wc -c < "$WORK/whole.csv") bytes"
