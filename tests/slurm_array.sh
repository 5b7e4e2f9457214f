#!/usr/bin/env bash
# slurm::array — configs/ci.yaml through Slurm: `shadowlab submit --slurm
# --tasks 4` on a single-node Slurm this test brings up itself (munged as
# the munge user, slurmctld and slurmd as root, a generated slurm.conf in a
# temporary folder, no systemd), the 4-task array and the merge job waited
# for, the merged store checked against the CI baseline like ci::baseline.
# Every daemon started here is stopped by its PID on the way out, failure
# included (trap). Skips (77) without Slurm or munge, or when not root
# (munged must run as the munge user).
set -u
bin=${1:?usage: slurm_array.sh path/to/shadowlab}
bin=$(realpath "$bin")
for t in munged slurmctld slurmd sbatch sinfo scontrol squeue scancel setpriv; do
  command -v "$t" >/dev/null || { echo "SKIP: $t not installed (scripts/setup.sh installs slurm-wlm and munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "SKIP: starting munged as the munge user needs root"; exit 77; }
id munge >/dev/null 2>&1 || { echo "SKIP: no munge user"; exit 77; }

tmp=$(mktemp -d)
chmod 755 "$tmp"   # munged (the munge user) reaches its folder through it
pids=()
stop() {
  rc=$?
  # jobs first (their steps are slurmd's children, not ours), then the daemons, newest first
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$tmp/slurmctld.ready" ]; then
    scancel --quiet ${array:-} ${merge:-} 2>/dev/null
    for _ in $(seq 1 50); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -TERM "${pids[$i]}" 2>/dev/null; done
  for p in "${pids[@]}"; do
    for _ in $(seq 1 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  # what slurmd started and left behind (a job step cut off by the stop is
  # re-parented to init): found by the SLURM_CONF of this test in its
  # environment, which only the daemons started here hand down (this shell
  # drops it first, so the scan's own processes do not carry it)
  unset SLURM_CONF
  for e in /proc/[0-9]*/environ; do
    [ -r "$e" ] || continue
    p=${e#/proc/}; p=${p%/environ}
    [ "$p" = $$ ] && continue
    { tr '\0' '\n' <"$e"; } 2>/dev/null | grep -qx "SLURM_CONF=$tmp/slurm.conf" && kill -KILL "$p" 2>/dev/null
  done
  if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
    for f in slurmctld.log slurmd.log munged.out out/slurm/task-0.log out/slurm/merge.log; do
      [ -f "$tmp/$f" ] && { echo "--- $f (tail)"; tail -n 15 "$tmp/$f"; }
    done
  fi
  rm -rf "$tmp"
  exit $rc
}
trap stop EXIT
trap 'exit 130' INT TERM
fail() { echo "FAIL $*"; exit 1; }

# munge: a fresh key, a socket of our own
mkdir -p "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chown -R munge:munge "$tmp/munge"
chmod 711 "$tmp/munge"   # munged wants its socket's folder reachable by every client
chmod 400 "$tmp/munge/munge.key"
sock=$tmp/munge/munge.socket
setpriv --reuid=munge --regid=munge --init-groups munged -F --socket="$sock" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" --log-file="$tmp/munge/munged.log" \
  >"$tmp/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 1 50); do [ -S "$sock" ] && break; sleep 0.1; done
[ -S "$sock" ] || fail "munged did not come up"

# slurm: one node, this host; ports from this process's id, so two runs do not collide
host=$(hostname -s)
port=$((20000 + ($$ % 20000) * 2))
cpus=$(nproc)
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=shadowlabtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N "$host" -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
touch "$tmp/slurmctld.ready"
up=0
for _ in $(seq 1 150); do
  if sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then up=1; break; fi
  sleep 0.2
done
[ $up -eq 1 ] || { cat "$tmp/slurmctld.out" "$tmp/slurmd.out"; sinfo 2>&1; fail "the node did not come up idle"; }

# the study: 4 tasks and the merge job
out=$tmp/out
"$bin" submit configs/ci.yaml --slurm --tasks 4 --out "$out" >"$tmp/submit.out" 2>&1 ||
  { cat "$tmp/submit.out"; fail "submit"; }
cat "$tmp/submit.out"
array=$(sed -n 's/^array job \([0-9]*\), merge job.*/\1/p' "$tmp/submit.out")
merge=$(sed -n 's/^array job [0-9]*, merge job \([0-9]*\).*/\1/p' "$tmp/submit.out")
[ -n "$array" ] && [ -n "$merge" ] || fail "no job ids in the submit output"
grep -q '^4 task(s)' "$tmp/submit.out" || fail "not 4 tasks"
state=
for _ in $(seq 1 1500); do
  state=$(scontrol -o show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2)
  case $state in COMPLETED|FAILED|CANCELLED|TIMEOUT|OUT_OF_MEMORY|NODE_FAIL) break ;; esac
  # a failed task leaves the merge pending forever (afterok): stop waiting
  scontrol -o show job "$array" 2>/dev/null | grep -qE 'JobState=(FAILED|CANCELLED|TIMEOUT)' &&
    { scontrol -o show job "$array"; fail "an array task failed"; }
  sleep 0.4
done
[ "$state" = COMPLETED ] || { scontrol -o show job "$merge"; fail "merge job ended $state"; }
for i in 0 1 2 3; do
  [ -f "$out/shards/task-$i/shadowlab.db" ] || fail "task $i left no shard"
done
cat "$out/slurm/merge.log"
n=$("$bin" validate configs/ci.yaml | head -1 | sed 's/.* \([0-9]*\) cell(s)/\1/')
grep -q "$n of $n cell(s) of the sweep stored, 0 missing" "$out/slurm/merge.log" || fail "merge did not bring every cell"
"$bin" check "$out/shadowlab.db" --baseline tests/baselines/ci.yaml --rows 60 || fail "the merged store against the CI baseline"
echo "1 passed, 0 failed"
