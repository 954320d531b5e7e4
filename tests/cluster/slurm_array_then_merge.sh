#!/usr/bin/env bash
# scripts/experiment-slurm against a throwaway single-node Slurm started here: its own munged (own
# key and socket), slurmctld and slurmd on free ports with their own slurm.conf and state in a
# temporary folder (SlurmUser = this user, proctrack/linuxproc, no cgroup). The script submits the
# study's job array (MaxArraySize=3 here, so several jobs per task) and the merge as a job depending on it; the test waits
# (bounded) for the merge and checks every job ran and the tables were built. The daemons are
# stopped and the folder removed however the test ends. Where Slurm cannot start here (packages
# missing, not root, no free port, a daemon that does not come up) the test says why and is SKIPPED.
#   slurm_array_then_merge.sh TRNKIT SCRIPTS_DIR STUDY
set -euo pipefail
trnkit=$1 scripts=$2 study=$3
skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }

for tool in munged mungekey slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (Debian packages munge slurmctld slurmd slurm-client; scripts/install-deps.sh)"
done
[[ $(id -u) -eq 0 ]] || skip "not root: slurmd must be root to start jobs as their user"

work=$(mktemp -d /tmp/trn-slurm.XXXXXX)  # short path: the munge socket name must fit sockaddr_un
chmod 700 "$work"
daemon_pids=()
# Daemons run in the foreground as children of this script; where setpriv can, they are also
# killed by the kernel when this script dies without running its trap (ctest's timeout kill).
start_daemon() {
  if setpriv --pdeathsig KILL true 2>/dev/null; then setpriv --pdeathsig KILL -- "$@" & else "$@" & fi
  daemon_pids+=("$!")
}
stop_all() {
  local pid
  for pid in "${daemon_pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${daemon_pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  # Jobs still running under our slurmd (its slurmstepd children) die with their step daemons.
  [[ -n ${keep_work:-} ]] || rm -rf -- "$work"
}
trap stop_all EXIT
show_logs() { tail -n 20 "$work"/*.log >&2 || true; }

# Free TCP ports: nothing listens there now (checked through /proc/net/tcp*, no extra tools).
port_in_use() { awk -v p="$(printf '%04X' "$1")" 'NR > 1 { split($2, a, ":"); if (a[2] == p) found = 1 } END { exit !found }' /proc/net/tcp /proc/net/tcp6 2>/dev/null; }
pick_port() {
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 40000))
    port_in_use "$p" || port_in_use "$((p + 1))" || { echo "$p"; return 0; }
  done
  return 1
}
ctl_port=$(pick_port) || skip "no free TCP port pair found for slurmctld"
node_port=$(pick_port) || skip "no free TCP port pair found for slurmd"

user=$(id -un)
node=$(hostname -s)
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool" "$work/out"
mungekey -c -k "$work/munge.key" >/dev/null 2>&1 || skip "mungekey could not create a key"
start_daemon munged -F -f --key-file="$work/munge.key" --socket="$work/munge.sock" --pid-file="$work/munged.pid" \
  --log-file="$work/munged.log" --seed-file="$work/munged.seed" >"$work/munged.out" 2>&1
for _ in $(seq 50); do [[ -S $work/munge.sock ]] && break; sleep 0.1; done
[[ -S $work/munge.sock ]] || { show_logs; skip "munged did not start (log above)"; }

cat >"$work/slurm.conf" <<CONF
ClusterName=trntest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$node_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$work/munge.sock
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MaxArraySize=3
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=trntest Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
# No cgroup use at all: Slurm 23.02 and newer (Debian 13 has 24.11) start the cgroup plugin in slurmd
# even with proctrack/linuxproc and fail where /sys/fs/cgroup is not mounted (a chroot, a
# container); 22.05 (Debian 12) has no "disabled" and needs no cgroup.conf.
slurm_version=$(slurmd -V 2>/dev/null | awk '{print $2}')
if [[ $slurm_version =~ ^([0-9]+)\.([0-9]+) ]] && (( BASH_REMATCH[1] * 100 + 10#${BASH_REMATCH[2]} >= 2302 )); then
  echo "CgroupPlugin=disabled" >"$work/cgroup.conf"
fi
export SLURM_CONF=$work/slurm.conf

start_daemon slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1
start_daemon slurmd -D -f "$SLURM_CONF" -N "$node" >"$work/slurmd.out" 2>&1
state=""
for _ in $(seq 60); do
  state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
  [[ $state == idle ]] && break
  for pid in "${daemon_pids[@]}"; do kill -0 "$pid" 2>/dev/null || { show_logs; skip "a Slurm daemon exited at start (logs above)"; }; done
  sleep 0.5
done
[[ $state == idle ]] || { show_logs; skip "the node did not become idle within 30 s (state '$state')"; }
echo "slurm: munged, slurmctld and slurmd up after $SECONDS s"

out=$work/out/$study
status=0
timeout 90 "$scripts/experiment-slurm" --wait --trnkit "$trnkit" "$study" --quick --no-plots --out "$out" \
  >"$work/submit.log" 2>&1 || status=$?
if ((status != 0)); then
  cat "$work/submit.log" >&2
  tail -n 20 "$out"/dispatch/slurm-*.log >&2 || true
  show_logs
  ((status == 124)) && fail "the array and merge did not finish within 90 s"
  fail "experiment-slurm failed (status $status)"
fi
n=$("$trnkit" experiment "$study" --quick --list-jobs=ids | wc -l)
# MaxArraySize=3 allows indices 1-2 only: the script must put up to ceil(n/2) jobs into each task
# (a task runs jobs of one inputs key; the study's two maps have n/2 jobs each).
per_task=$(((n + 1) / 2))
tasks=$(((n + per_task - 1) / per_task))
[[ $("$trnkit" experiment "$study" --quick --list-jobs=keys | awk '{ print $2 }' | sort -u | wc -l) -eq $tasks ]] || fail "expected $tasks inputs keys"
grep -q "MaxArraySize is 3: up to $per_task jobs per task" "$work/submit.log" || { cat "$work/submit.log" >&2; fail "jobs per task not raised to fit MaxArraySize"; }
[[ $(find "$out/jobs" -maxdepth 1 -name '*.json' | wc -l) -eq $n ]] || fail "expected $n job outputs"
[[ $(find "$out/dispatch" -name 'slurm-*_*.log' | wc -l) -eq $tasks ]] || fail "expected $tasks array task logs"
grep -q "$n jobs in $tasks array tasks" "$work/submit.log" || fail "the submission did not report $tasks tasks"
[[ -s $out/results.md && -s $out/provenance.json ]] || fail "no tables after the merge job"
! grep -q PARTIAL "$out/results.md" || fail "the merge is partial"
echo "slurm: $n jobs in $tasks array tasks, then the dependent merge built the tables ($SECONDS s)"

# A study whose jobs fail on the nodes (a device this machine lacks is found only when a job creates
# its backend; an unknown family is refused before anything is submitted): the merge never runs
# (Slurm cancels it) and the script says so with a non-zero status.
status=0
timeout 60 "$scripts/experiment-slurm" --jobs-per-task 4 --wait --trnkit "$trnkit" "$study" --quick --no-plots \
  --backend opencl:99 --out "$work/out/failing" >"$work/failing.log" 2>&1 || status=$?
((status != 124)) || fail "the failing submission did not end within 60 s"
((status != 0)) || fail "failed tasks did not fail the submission"
grep -q "ended CANCELLED" "$work/failing.log" || { cat "$work/failing.log" >&2; fail "the merge was not cancelled"; }
grep -q "opencl:99" "$work/out/failing/dispatch"/slurm-*_1.log || fail "the task log does not name the failure"
[[ ! -e $work/out/failing/results.md ]] || fail "the merge ran after failed tasks"
echo "slurm: failed tasks cancelled the merge ($SECONDS s in all)"
