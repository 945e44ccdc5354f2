#!/usr/bin/env bash
# batch_cli.sh - `facet batch`: JSON-lines and list jobs, the report, skipping and --force, shards, bad jobs files.
# Usage: batch_cli.sh FACET SCRATCH. Prints one line per case and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
models=/usr/share/assimp/models
mkdir -p "$scratch"
rm -rf "${scratch:?}"/*
cd "$scratch" || exit 1

# Four jobs, one of them a model that does not exist; outputs in folders the batch makes.
cat >jobs.jsonl <<EOF
{"model": "$models/OBJ/box.obj", "output": "out/{stem}.png", "resolution": [64, 48]}
{"model": "$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", "output": "out/{n:03}.png", "resolution": "64,48", "camera-azimuth-angle": 40}

{"model": "missing.obj", "output": "out/missing.png"}
{"model": "$models/STL/Spider_binary.stl", "output": "out/deep/{stem}.png", "resolution": [48, 48], "no-background": true, "output-mask": "out/deep/{stem}_mask.png"}
EOF
expected="out/001.png out/box.png out/deep/Spider_binary.png out/deep/Spider_binary_mask.png"
listing() { (cd "$1" && find out -type f | sort | tr '\n' ' ' | sed 's/ $//'); }
# The report's statuses in the jobs' order (jobs run on every core, so lines come in the order they finish).
statuses() {
  python3 -c 'import json, sys
print(" ".join(e["status"] for e in sorted((json.loads(l) for l in open(sys.argv[1])), key=lambda e: e["line"])))' "$1"
}

"$facet" batch jobs.jsonl --report report.jsonl --quiet 2>first.log
status=$?
if [ "$status" = 1 ] && [ "$(listing .)" = "$expected" ] && [ "$(statuses report.jsonl)" = "ok ok failed ok" ] &&
  grep -q '^facet: error: missing.obj: no such file' first.log; then
  ok "jobs run, the broken one reported: $(statuses report.jsonl)"
else
  bad "first run" "exit $status, files '$(listing .)', report '$(statuses report.jsonl 2>&1)'"
fi
sums() { (cd "$1" && find out -type f | sort | xargs md5sum); }
# The image data of each PNG in FOLDER/out (its filtered rows, inflated): what a rerun must reproduce. igzip may
# deflate the same rows to other, equally valid bytes from one run to another on a loaded machine.
images() {
  python3 -c 'import glob, hashlib, struct, sys, zlib
for path in sorted(glob.glob(sys.argv[1] + "/out/*.png")):
    data, pos, idat = open(path, "rb").read(), 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        idat += data[pos + 8:pos + 8 + n] if kind == b"IDAT" else b""
        pos += 12 + n
    print(hashlib.md5(data[16:24] + zlib.decompress(idat)).hexdigest(), path[len(sys.argv[1]) + 1:])' "$1"
}
first=$(sums .)
# Each job is its own render: the flags of one job (an azimuth, a resolution) never carry over to the next.
"$facet" render "$models/STL/Spider_binary.stl" --resolution 48,48 --no-background --output alone.png 2>/dev/null
"$facet" render "$models/OBJ/box.obj" --resolution 64,48 --output alone_box.png 2>/dev/null
if cmp -s alone.png out/deep/Spider_binary.png && cmp -s alone_box.png out/box.png; then
  ok "batch images are byte for byte those of facet render with the same flags"
else
  bad "batch vs render" "out/deep/Spider_binary.png or out/box.png differs from facet render's"
fi

# A rerun skips what exists; --force renders it again, byte for byte the same.
"$facet" batch jobs.jsonl --report again.jsonl --quiet 2>/dev/null
if [ "$(statuses again.jsonl)" = "skipped skipped failed skipped" ] && [ "$(sums .)" = "$first" ]; then
  ok "rerun skips the jobs whose outputs exist"
else
  bad "rerun" "report '$(statuses again.jsonl 2>&1)'"
fi
"$facet" batch jobs.jsonl --report forced.jsonl --force --quiet 2>/dev/null
if [ "$(statuses forced.jsonl)" = "ok ok failed ok" ] && [ "$(sums .)" = "$first" ]; then
  ok "--force renders again, identical bytes"
else
  bad "--force" "report '$(statuses forced.jsonl 2>&1)'"
fi

# Shards: two halves, and the same shares through Slurm's and Kubernetes' variables, make the files of one run.
mkdir -p shards auto
(cd shards && "$facet" batch ../jobs.jsonl --shard 0/2 --quiet 2>/dev/null; "$facet" batch ../jobs.jsonl --shard 1/2 --quiet 2>/dev/null)
(cd auto && SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_COUNT=2 "$facet" batch ../jobs.jsonl --shard auto --quiet 2>/dev/null
  JOB_COMPLETION_INDEX=0 "$facet" batch ../jobs.jsonl --shard auto --shards 2 --quiet 2>/dev/null)
if [ -n "$first" ] && [ "$(sums shards)" = "$first" ] && [ "$(sums auto)" = "$first" ]; then
  ok "shards 0/2 + 1/2, and Slurm's and Kubernetes' shares, give the unsharded files"
else
  bad "shards" "shards: '$(listing shards)', auto: '$(listing auto)'"
fi
# Three shards under GNU parallel, as docs/BATCH.md shows it, make exactly the files of one run.
mkdir -p par
(cd par && parallel --will-cite "$facet" batch ../jobs.jsonl --quiet --threads 1 --shard {}/3 ::: 0 1 2 2>/dev/null)
if [ -n "$first" ] && [ "$(sums par)" = "$first" ]; then
  ok "3 shards under GNU parallel give the unsharded files"
else
  bad "GNU parallel" "'$(listing par)'"
fi
(cd auto && rm -rf out && JOB_COMPLETION_INDEX=1 "$facet" batch ../jobs.jsonl --shard auto --shards 2 --quiet 2>/dev/null)
if [ "$(listing auto)" = "out/001.png out/deep/Spider_binary.png out/deep/Spider_binary_mask.png" ]; then
  ok "shard 1 of 2 renders jobs 1 and 3"
else
  bad "shard 1 of 2" "'$(listing auto)'"
fi

# SIGTERM midway: the jobs in flight finish, nothing partial or temporary is left, and a rerun completes the set
# with the images of an uninterrupted run. A sanitized build renders each job ten times slower, so fewer jobs, of
# one sample each (the sanitized unit tests cover multisampling), still leave the signal arriving midway; the
# release build writes a job's PNG in about a millisecond, so it takes 400, which outlast a loaded poll.
many=400 samples=4
[ -n "${FACET_E2E_SANITIZED:-}" ] && many=40 samples=1
python3 -c 'import json, sys
for n in range(int(sys.argv[2])): print(json.dumps({"model": sys.argv[1], "samples": int(sys.argv[3])}))' \
  "$models/OBJ/WusonOBJ.obj" "$many" "$samples" >many.txt
mkdir -p stopped whole
# interrupt FOLDER SIGNAL: runs the batch in FOLDER, sends SIGNAL once its first output exists (a fixed sleep is
# too short on a loaded machine under the sanitizers), and returns the batch's exit status.
interrupt() {
  (cd "$1" && exec "$facet" batch ../many.txt --output 'out/{n}.png' --quiet 2>err.log) &
  local pid=$!
  for _ in $(seq 600); do
    compgen -G "$1/out/*.png" >/dev/null && break
    sleep 0.1
  done
  kill "-$2" "$pid"
  wait "$pid"
}
interrupt stopped TERM
stopped_status=$?
made=$(find stopped/out -name '*.png' 2>/dev/null | wc -l)
temporaries=$(find stopped -name '.*' -type f | wc -l)
complete=$(for f in stopped/out/*.png; do tail -c 8 "$f" | grep -c IEND; done | grep -c 0)
(cd stopped && "$facet" batch ../many.txt --output 'out/{n}.png' --quiet)
resumed_status=$?
(cd whole && "$facet" batch ../many.txt --output 'out/{n}.png' --quiet)
if [ "$stopped_status" = 143 ] && [ "$made" -gt 0 ] && [ "$made" -lt "$many" ] && [ "$temporaries" = 0 ] &&
  [ "$complete" = 0 ] && [ "$resumed_status" = 0 ] && [ "$(images stopped)" = "$(images whole)" ]; then
  ok "SIGTERM after $made of $many jobs: no partial or temporary file; the rerun matches an uninterrupted run"
else
  bad "SIGTERM" "exit $stopped_status, $made made, $temporaries temporaries, $complete incomplete, rerun $resumed_status"
fi

# SIGKILL (as power loss) cannot be caught: whatever temporaries it leaves, the rerun removes those of its own
# outputs whose writer is dead, keeps a live writer's and other files', and finishes with the uninterrupted images.
mkdir -p killed/out
interrupt killed KILL
killed_status=$?
last=$((many - 1))
rm -f "killed/out/$last.png"
touch "killed/out/.$last.png.999999999.0.tmp" "killed/out/.$last.png.$$.3.tmp" killed/out/.other.png.999999999.0.tmp
(cd killed && "$facet" batch ../many.txt --output 'out/{n}.png' --quiet)
resumed_status=$?
left=$(cd killed/out && find . -name '.*' -type f | sort | tr '\n' ' ')
rm -f "killed/out/.$last.png.$$.3.tmp" killed/out/.other.png.999999999.0.tmp
if [ "$killed_status" = 137 ] && [ "$resumed_status" = 0 ] && [ "$(images killed)" = "$(images whole)" ] &&
  [ "$left" = "./.$last.png.$$.3.tmp ./.other.png.999999999.0.tmp " ]; then
  ok "SIGKILL: the rerun removes dead writers' temporaries and matches an uninterrupted run"
else
  unlike=$(diff <(images killed) <(images whole) | head -4 | tr '\n' ' ')
  bad "SIGKILL" "exit $killed_status, rerun $resumed_status, hidden files left: $left; unlike the uninterrupted run: $unlike"
fi

# A plain list of models with an output template.
printf '# thumbnails\n%s\n\n%s\n' "$models/OBJ/box.obj" "$models/PLY/cube_binary.ply" >list.txt
mkdir -p list
if (cd list && "$facet" batch ../list.txt --output 'out/{n}_{stem}.png' --quiet) &&
  [ "$(listing list)" = "out/0_box.png out/1_cube_binary.png" ]; then
  ok "a list of models with --output"
else
  bad "list" "'$(listing list)'"
fi

# Bad jobs files: one error line naming the line, exit 1 (2 for usage), before anything is rendered.
expect_refused() {  # NAME STATUS TEXT FILE-CONTENT [FLAGS...]
  local name=$1 want=$2 text=$3 content=$4
  shift 4
  mkdir -p "bad_$name"
  printf '%s' "$content" >"bad_$name/jobs"
  (cd "bad_$name" && "$facet" batch jobs "$@" >stdout 2>stderr)
  local got=$?
  if [ "$got" = "$want" ] && [ "$(wc -l <"bad_$name/stderr")" = 1 ] && grep -qF -- "$text" "bad_$name/stderr" &&
    [ ! -e "bad_$name/out" ]; then
    ok "$name ($got): $(cat "bad_$name/stderr")"
  else
    bad "$name" "exit $got: $(tr '\n' '|' <"bad_$name/stderr")"
  fi
}
good="{\"model\": \"$models/OBJ/box.obj\", \"output\": \"out/a.png\"}"
expect_refused not_json 1 "jobs: line 2: not valid JSON" "$good"$'\n{"model": \n'
expect_refused unknown_key 1 "line 1: " "{\"model\": \"$models/OBJ/box.obj\", \"output\": \"out/a.png\", \"bogus\": 1}"$'\n'
expect_refused wrong_type 1 'line 1: "resolution": expected a string, number, boolean or list' \
  "{\"model\": \"$models/OBJ/box.obj\", \"output\": \"out/a.png\", \"resolution\": {\"w\": 1}}"$'\n'
expect_refused no_model 1 'line 2: "model" (a string) is missing' "$good"$'\n{"output": "out/b.png"}\n'
expect_refused bad_value 1 "line 1: --resolution" \
  "{\"model\": \"$models/OBJ/box.obj\", \"output\": \"out/a.png\", \"resolution\": [0, 5]}"$'\n'
expect_refused same_output 2 "lines 1 and 2 would both write" "$good"$'\n'"$good"$'\n'
expect_refused list_without_output 2 "--output: a list of models needs an output template" "$models/OBJ/box.obj"$'\n'
expect_refused bad_shard 2 "--shard: shard 2 of 2 does not exist" "$good"$'\n' --shard 2/2
expect_refused no_scheduler 2 "--shard auto: neither" "$good"$'\n' --shard auto

finish
