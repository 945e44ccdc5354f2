#!/usr/bin/env bash
# kubernetes_index.sh - docs/BATCH.md's Kubernetes Indexed Job, without a cluster: its container command run once
# for each JOB_COMPLETION_INDEX the Job would give (0 .. completions - 1), with /data a scratch folder; their
# outputs together must be one unsharded batch's, byte for byte, and no file more.
# Usage: kubernetes_index.sh FACET SCRATCH SOURCE_DIR
set -uo pipefail
facet=$(realpath "$1")
scratch=$2
source_dir=$3
# shellcheck source=lib/common.bash
source "$(dirname "$0")/lib/common.bash"
rm -rf "$scratch"
mkdir -p "$scratch/bin" "$scratch/one" "$scratch/indexed"
ln -s "$facet" "$scratch/bin/facet"
export PATH=$scratch/bin:$PATH

# The manifest's container: its working folder, its command with /data as a scratch folder, and the index count.
if ! python3 - "$source_dir/docs/BATCH.md" "$scratch/indexed" >"$scratch/command.txt" 2>"$scratch/manifest.err" <<'PY'
import re, shlex, sys
import yaml
text = open(sys.argv[1]).read()
block = re.search(r"### Kubernetes\n.*?```yaml\n(.*?)```", text, re.S).group(1)
job = yaml.safe_load(block)
spec = job["spec"]
assert job["kind"] == "Job" and spec["completionMode"] == "Indexed", "an Indexed Job"
container = spec["template"]["spec"]["containers"][0]
data = sys.argv[2]
print(spec["completions"])
print(container["workingDir"].replace("/data", data, 1))
print(shlex.join(arg.replace("/data", data, 1) for arg in container["command"]))
PY
then
  bad "docs/BATCH.md holds an Indexed Job manifest" "$(tail -1 "$scratch/manifest.err")"
  finish
  exit 1
fi
{ read -r completions; read -r workdir; read -r command; } <"$scratch/command.txt"
ok "the manifest: $completions indices, in $workdir: $command"

# Jobs of four formats in one file, at their own angles, each writing its own image.
python3 - <<'PY' >"$scratch/jobs.jsonl"
import json
root = "/usr/share/assimp/models"
models = ["OBJ/WusonOBJ.obj", "PLY/Wuson.ply", "STL/Spider_binary.stl", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"]
for k in range(14):
    print(json.dumps({"model": f"{root}/{models[k % 4]}", "output": f"thumbs/{k:02}.png", "resolution": [96, 96],
                      "camera-azimuth-angle": k * 25}))
PY
cp "$scratch/jobs.jsonl" "$scratch/indexed/jobs.jsonl"
(cd "$scratch/one" && "$facet" batch ../jobs.jsonl --quiet) || bad "one unsharded batch"

failed_indices=""
for ((index = 0; index < completions; index++)); do
  # shellcheck disable=SC2086  # the command is meant to split into its words
  (cd "$workdir" && eval "JOB_COMPLETION_INDEX=$index $command") 2>>"$scratch/indexed.err" ||
    failed_indices+=" $index"
done
[ -z "$failed_indices" ] && ok "each index's command succeeds" || bad "indices$failed_indices failed" "$(tail -1 "$scratch/indexed.err")"
rm "$scratch/indexed/jobs.jsonl"
if diff -r "$scratch/one" "$scratch/indexed" >"$scratch/diff.txt"; then
  ok "the indices' outputs together are the unsharded batch's: $(find "$scratch/one" -name '*.png' | wc -l) images, byte for byte"
else
  bad "the indices' outputs together are the unsharded batch's" "$(head -3 "$scratch/diff.txt")"
fi
# One index alone renders only its share: every completions-th job from its own.
mkdir -p "$scratch/alone" && cp "$scratch/jobs.jsonl" "$scratch/alone/"
(cd "$scratch/alone" && JOB_COMPLETION_INDEX=1 "$facet" batch jobs.jsonl --shard auto --shards "$completions" --quiet)
expected=$(seq -f '%02g.png' 1 "$completions" 13 | tr '\n' ' ')
made=$(ls "$scratch/alone/thumbs" | tr '\n' ' ')
[ "$made" = "$expected" ] && ok "index 1 of $completions renders jobs $made" || bad "index 1's share" "made $made, expected $expected"
finish
