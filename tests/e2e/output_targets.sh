#!/usr/bin/env bash
# output_targets.sh - outputs to devices, FIFOs, symlinks, "-" and /dev/full: bytes arrive, nothing is replaced.
# Usage: output_targets.sh FACET SCRATCH. Prints one line per case and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
box=/usr/share/assimp/models/OBJ/box.obj
mkdir -p "$scratch"
rm -rf "${scratch:?}"/* "$scratch"/.[!.]*
render=("$facet" render "$box" --resolution 64,48)

# The bytes every target below must receive: the same render written to a plain new file.
"${render[@]}" --output "$scratch/reference.png" 2>/dev/null || bad "reference render" "exit $?"

# same NAME FILE: FILE holds exactly the reference PNG.
same() {
  if cmp -s "$scratch/reference.png" "$2"; then ok "$1: the PNG arrived whole"; else bad "$1" "bytes differ"; fi
}
no_temporaries() {
  if compgen -G "$scratch/.*.tmp" >/dev/null; then bad "$1" "a temporary file was left"; fi
}

# A character device: a copy of /dev/null (root can make one; others test /dev/null itself, which they could not
# replace anyway). It must still be the device afterwards, and must have swallowed the bytes.
null=$scratch/null
mknod "$null" c 1 3 2>/dev/null || null=/dev/null
if "${render[@]}" --output "$null" 2>"$scratch/null.err" && [ -c "$null" ] && [ ! -s "$null" ]; then
  ok "device $null: written, still a character device"
else
  bad "device $null" "exit or type wrong: $(cat "$scratch/null.err")"
fi
no_temporaries "device"

# A FIFO: a reader receives the bytes, and the FIFO stays a FIFO.
mkfifo "$scratch/fifo"
cat "$scratch/fifo" >"$scratch/from_fifo.png" &
reader=$!
timeout 60 "${render[@]}" --output "$scratch/fifo" 2>"$scratch/fifo.err" || bad "fifo" "exit $?: $(cat "$scratch/fifo.err")"
wait "$reader"
[ -p "$scratch/fifo" ] && ok "fifo: still a FIFO" || bad "fifo" "no longer a FIFO"
same "fifo" "$scratch/from_fifo.png"

# A symlink to /proc/self/fd/1, and "-": standard output receives the bytes; the link stays a link.
ln -s /proc/self/fd/1 "$scratch/stdout_link"
"${render[@]}" --output "$scratch/stdout_link" >"$scratch/from_link.png" 2>"$scratch/link.err" ||
  bad "stdout link" "exit $?: $(cat "$scratch/link.err")"
[ -L "$scratch/stdout_link" ] && ok "stdout link: still a symlink" || bad "stdout link" "replaced"
same "stdout link" "$scratch/from_link.png"
"${render[@]}" --output - >"$scratch/from_dash.png" 2>"$scratch/dash.err" || bad "-" "exit $?: $(cat "$scratch/dash.err")"
same "--output -" "$scratch/from_dash.png"

# A symlink to a regular file: the file it points to is replaced, the link is kept.
printf 'old' >"$scratch/real.png"
ln -s real.png "$scratch/link.png"
"${render[@]}" --output "$scratch/link.png" 2>/dev/null
[ -L "$scratch/link.png" ] && ok "link to a file: still a symlink" || bad "link to a file" "replaced"
same "link to a file" "$scratch/real.png"
no_temporaries "link to a file"

# /dev/full: a clean one-line error, exit 1, and /dev/full untouched.
"${render[@]}" --output /dev/full 2>"$scratch/full.err"
status=$?
if [ "$status" -eq 1 ] && [ "$(wc -l <"$scratch/full.err")" -eq 1 ] && grep -q "^facet: error: /dev/full: " \
  "$scratch/full.err" && [ -c /dev/full ]; then
  ok "/dev/full: $(cat "$scratch/full.err")"
else
  bad "/dev/full" "exit $status: $(cat "$scratch/full.err")"
fi

# A later output failing removes the files written before it, but never a device written before it.
rm -f "$scratch/first.png"
"${render[@]}" --output "$scratch/first.png" --output-depth /dev/full 2>/dev/null
[ ! -e "$scratch/first.png" ] && ok "failed depth: the colour file is removed" || bad "failed depth" "colour file left"
"${render[@]}" --output "$null" --output-depth /dev/full 2>/dev/null
[ -c "$null" ] && ok "failed depth: the device written before is still there" || bad "failed depth" "device removed"

# Formats follow the name: refused before rendering, exit 2, nothing written.
for args in "--output $scratch/x.jpg" "--output $scratch/x.png --output-depth $scratch/d.png" \
  "--output $scratch/x.png --output-ids $scratch/i.exr" "--output $scratch/x.png --output-camera $scratch/c.txt"; do
  # shellcheck disable=SC2086  # the cases are word lists
  "${render[@]}" $args 2>"$scratch/format.err"
  status=$?
  if [ "$status" -eq 2 ] && grep -q "facet writes" "$scratch/format.err" && ! compgen -G "$scratch/[xdic].*" >/dev/null
  then
    ok "refused: $(cat "$scratch/format.err")"
  else
    bad "format of $args" "exit $status: $(cat "$scratch/format.err")"
  fi
done
"${render[@]}" --output "$scratch/UPPER.PNG" --output-depth "$scratch/d.EXR" 2>/dev/null &&
  [ -s "$scratch/UPPER.PNG" ] && ok "extensions in capitals are accepted" || bad "capital extensions"
finish
