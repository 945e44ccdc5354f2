#!/usr/bin/env bash
# slurm.sh - docs/BATCH.md's Slurm array job on a real one-node Slurm cluster: munged, slurmctld and slurmd from
# Debian's packages, started on localhost with a generated configuration and stopped at the end. The array's
# outputs together must be one unsharded batch's, byte for byte; then a task cancelled midway (scancel) leaves no
# partial file, and that index submitted again alone completes the set.
# Usage: slurm.sh FACET SCRATCH SOURCE_DIR. Needs root (slurmd runs jobs as their users); else exits 77 (skipped).
set -uo pipefail
facet=$(realpath "$1")
scratch=$2
source_dir=$3
# shellcheck source=lib/common.bash
source "$(dirname "$0")/lib/common.bash"
if [ "$(id -u)" -ne 0 ]; then
  echo "skipped: slurmd needs root to run jobs"
  exit 77
fi
command -v slurmctld >/dev/null && command -v munged >/dev/null || "$source_dir/scripts/deps.sh"
rm -rf "$scratch"
mkdir -p "$scratch"/{munge,state,spool,log,bin,one,cluster}
scratch=$(cd "$scratch" && pwd)
chmod 700 "$scratch/munge"
ln -s "$facet" "$scratch/bin/facet"
export PATH=$scratch/bin:$PATH  # sbatch passes the environment on to the tasks

# The cluster: munge's key and socket, and slurm.conf, all in the scratch folder, on two free ports.
dd if=/dev/urandom of="$scratch/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 600 "$scratch/munge/munge.key"
read -r port_ctld port_d < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
node=$(hostname -s)
export SLURM_CONF=$scratch/slurm.conf
cat >"$SLURM_CONF" <<CONF
ClusterName=facet-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port_ctld
SlurmdPort=$port_d
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$scratch/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/log/slurmctld.log
SlurmdLogFile=$scratch/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
SwitchType=switch/none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
ReturnToService=2
KillWait=10
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
stop_cluster() {
  scontrol shutdown >/dev/null 2>&1
  for pid in "$scratch/slurmctld.pid" "$scratch/slurmd.pid" "$scratch/munge/munged.pid"; do
    [ -f "$pid" ] && kill "$(cat "$pid")" 2>/dev/null
  done
  return 0
}
trap stop_cluster EXIT
munged --force --socket="$scratch/munge/munge.socket" --key-file="$scratch/munge/munge.key" \
  --log-file="$scratch/log/munged.log" --pid-file="$scratch/munge/munged.pid" --seed-file="$scratch/munge/seed" ||
  { bad "munged starts" "$(tail -2 "$scratch/log/munged.log")"; finish; exit 1; }
slurmctld -i && slurmd || { bad "slurmctld and slurmd start" "$(tail -2 "$scratch/log/slurmctld.log")"; finish; exit 1; }
for _ in $(seq 100); do
  [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && break
  sleep 0.2
done
[ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && ok "a one-node Slurm cluster is up ($node, $(nproc) CPUs)" ||
  { bad "the node is idle" "$(sinfo 2>&1 | tail -1)"; finish; exit 1; }

# The batch script, as docs/BATCH.md gives it.
python3 - "$source_dir/docs/BATCH.md" >"$scratch/thumbnails.sh" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
print(re.search(r"### Slurm\n.*?```bash\n(.*?)```", text, re.S).group(1), end="")
PY
tasks=$(sed -n 's/^#SBATCH --array=0-\([0-9]*\)$/\1/p' "$scratch/thumbnails.sh")
tasks=$((tasks + 1))
grep -q -- "--shards $tasks " "$scratch/thumbnails.sh" && ok "docs/BATCH.md's script: $tasks tasks" ||
  bad "docs/BATCH.md's script has an --array of 0-N and --shards N+1" "$(cat "$scratch/thumbnails.sh")"

# 48 jobs of real models, 12 a task, each a few tenths of a second, so that a task can be cancelled midway.
python3 - <<'PY' >"$scratch/jobs.jsonl"
import json
root = "/usr/share/assimp/models"
models = ["OBJ/WusonOBJ.obj", "OBJ/spider.obj", "PLY/Wuson.ply", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"]
for k in range(48):
    print(json.dumps({"model": f"{root}/{models[k % 4]}", "output": f"out/{k:02}.png", "resolution": [1024, 1024],
                      "samples": 8, "camera-azimuth-angle": k * 7.5}))
PY
cp "$scratch/jobs.jsonl" "$scratch/one/" && cp "$scratch/jobs.jsonl" "$scratch/cluster/"
(cd "$scratch/one" && "$facet" batch jobs.jsonl --quiet) || bad "one unsharded batch"

# Submits the script with extra sbatch arguments from the cluster folder and waits for the job to leave the queue.
submit_and_wait() {
  local id
  id=$(cd "$scratch/cluster" && sbatch --parsable "$@" ../thumbnails.sh) || return 1
  for _ in $(seq 600); do
    [ -z "$(squeue -h -j "$id" 2>/dev/null)" ] && { echo "$id"; return 0; }
    sleep 0.2
  done
  return 1
}
# Compares the cluster's outputs with the unsharded run's: same files, same bytes, nothing else (no temporaries).
same_as_one() {
  diff -r -x jobs.jsonl -x 'slurm-*.log' -x 'report_*.jsonl' "$scratch/one" "$scratch/cluster" >"$scratch/diff.txt"
}

if id=$(submit_and_wait) && same_as_one; then
  ok "the array job ($id) makes the unsharded batch's $(ls "$scratch/one/out" | wc -l) images, byte for byte"
else
  bad "the array job makes the unsharded batch's images" "$(head -3 "$scratch/diff.txt") $(tail -2 "$scratch"/cluster/slurm-*.log)"
fi

# Again from nothing; task 2 is cancelled once it has written its first image.
rm -rf "$scratch/cluster/out" "$scratch"/cluster/slurm-*.log "$scratch"/cluster/report_*.jsonl
id=$(cd "$scratch/cluster" && sbatch --parsable ../thumbnails.sh)
cancelled=no
for _ in $(seq 600); do
  if [ -f "$scratch/cluster/out/02.png" ]; then
    scancel "${id}_2" && cancelled=yes
    break
  fi
  sleep 0.05
done
for _ in $(seq 600); do
  [ -z "$(squeue -h -j "$id" 2>/dev/null)" ] && break
  sleep 0.2
done
task2=$(seq -f '%02g.png' 2 "$tasks" 47)
left=0
for f in $task2; do [ -f "$scratch/cluster/out/$f" ] || left=$((left + 1)); done
stray=$(find "$scratch/cluster/out" -name '.*' | wc -l)
if [ "$cancelled" = yes ] && [ "$left" -gt 0 ] && [ "$stray" -eq 0 ]; then
  ok "task 2, cancelled midway, left $left of its 12 images unmade and no temporary file"
else
  bad "task 2 cancelled midway" "cancelled: $cancelled, unmade: $left, temporaries: $stray"
fi
partial=0
for f in "$scratch"/cluster/out/*.png; do cmp -s "$f" "$scratch/one/out/$(basename "$f")" || partial=$((partial + 1)); done
[ "$partial" -eq 0 ] && ok "every image written before the cancel is whole and the unsharded batch's" ||
  bad "images written before the cancel" "$partial differ from the unsharded batch's"
if id=$(submit_and_wait --array=2) && same_as_one; then
  ok "task 2 submitted again alone ($id) completes the set: the unsharded batch's images, byte for byte"
else
  bad "task 2 submitted again completes the set" "$(head -3 "$scratch/diff.txt")"
fi
# On a failure, what the cluster said: its daemons' last lines and the tasks' logs.
if [ "$failed" -gt 0 ]; then
  tail -n 5 "$scratch"/log/*.log "$scratch"/cluster/slurm-*.log 2>/dev/null
  cat "$scratch/diff.txt" 2>/dev/null | head -5
fi
finish
