#!/usr/bin/env bash
# A sweep as a Slurm job array on a one-node Slurm started here on localhost, merged with
# `glint merge` and compared with the unsharded run byte for byte (ctest: sweep_slurm, label
# slurm, configuration slurm only: `ctest --test-dir build -C slurm -L slurm`).
#
# Everything lives in a temporary folder: a munge key and munged (its own socket), a slurm.conf
# for this host (one node, its cores, the folder's state, spool, logs and PID files), slurmctld and
# slurmd in the foreground, the array job, and the shards. Nothing under /etc is read or written
# (SLURM_CONF points every client at the folder's slurm.conf) and every daemon started here is
# stopped here, by the PID it was given, when the script ends.
#
# Needs: Debian packages slurm-wlm and munge (slurmctld, slurmd, sbatch, sinfo, munged), and root:
# slurmd starts job steps as the submitting user, and munged and slurmd check that their key,
# spool and socket are owned by the user that runs them. Ports: GLINT_SLURM_PORTS="CTLD SLURMD"
# (default "16817 16818").
# Usage: slurm_array.sh GLINT TRACES_DIR
set -euo pipefail
glint=$(realpath "$1")
traces=$(realpath "$2")
read -r ctld_port slurmd_port <<<"${GLINT_SLURM_PORTS:-16817 16818}"

for tool in munged slurmctld slurmd sbatch sinfo; do
  if ! command -v "$tool" >/dev/null; then
    echo "FAIL: $tool is missing (apt-get install slurm-wlm munge)"
    exit 1
  fi
done
if [[ $(id -u) -ne 0 ]]; then
  echo "FAIL: run as root (slurmd and munged check that their files belong to the user)"
  exit 1
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/glint_sweep_slurm.XXXXXX")
chmod 0700 "$work"
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [[ $status -ne 0 ]]; then
    for log in "$work"/*.log "$work"/slurm-*.out; do
      [[ -f $log ]] && { echo "---- $log"; tail -n 20 "$log"; }
    done
  fi
  rm -rf "$work"
}
trap cleanup EXIT

# munge: a fresh key, its own socket, in the foreground (-F) so that its PID is ours.
dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 status=none
chmod 0400 "$work/munge.key"
munged -F --force --key-file="$work/munge.key" --socket="$work/munge.socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed" \
  2>"$work/munged.stderr.log" &
pids+=($!)
for _ in $(seq 50); do [[ -S $work/munge.socket ]] && break; sleep 0.1; done
[[ -S $work/munge.socket ]] || { echo "FAIL: munged did not start"; exit 1; }

host=$(hostname -s)
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<CONF
ClusterName=glinttest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
PlugStackConfig=$work/plugstack.conf
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=glint Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
: >"$work/plugstack.conf"
export SLURM_CONF=$work/slurm.conf

# In the foreground (-D), so that their PIDs are ours to stop; their messages go to the logs.
slurmctld -D -f "$SLURM_CONF" 2>"$work/slurmctld.stderr.log" &
pids+=($!)
slurmd -D -f "$SLURM_CONF" 2>"$work/slurmd.stderr.log" &
pids+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  [[ $state == idle* ]] && break
  sleep 0.2
done
[[ ${state:-} == idle* ]] || { echo "FAIL: the node did not come up (state '${state:-}')"; exit 1; }

input=$traces/multi_light.vec
grids=(--grid 'horner:degree=2..5,in=uq1.11|uq1.15' --grid 'lut:bits=4..8' --grid pow
       --grid 'hast:d=2..4' --grid 'schlick:divider=pipelined|iterative')
printf -v grid_words '%q ' "${grids[@]}"
# The recipe of src/cli/guide/sweep.md: one array task per shard, each writing shardK.json.
cat >"$work/sweep.sbatch" <<JOB
#!/usr/bin/env bash
#SBATCH --array=0-3
#SBATCH --cpus-per-task=1
#SBATCH --output=$work/slurm-%A_%a.out
exec $(printf %q "$glint") sweep $(printf %q "$input") $grid_words --jobs 1 \\
  --shard \${SLURM_ARRAY_TASK_ID}/4 -o $(printf %q "$work")/shard\${SLURM_ARRAY_TASK_ID}.json
JOB
start=$(date +%s)
sbatch --wait --chdir="$work" "$work/sweep.sbatch" >"$work/sbatch.txt"
echo "array job $(cut -d' ' -f4 "$work/sbatch.txt"): 4 tasks in $(( $(date +%s) - start )) s"

"$glint" sweep "$input" "${grids[@]}" --jobs 1 -o "$work/all.json" >/dev/null
"$glint" merge "$work"/shard{0,1,2,3}.json -o "$work/merged.json" >/dev/null
cmp "$work/all.json" "$work/merged.json"
echo "PASS: 4 shards as a Slurm array merge to the unsharded run's bytes"
