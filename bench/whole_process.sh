#!/usr/bin/env bash
# whole_process.sh - `facet render MODEL --output f.png` as a user times it, against the reference renderer doing
# the same job (Assimp loads the file, llvmpipe draws one frame, the PNG is written), as whole processes.
# Usage: bench/whole_process.sh FACET GLREF [ROUNDS] [SAMPLES]. 1920x1080, 2 threads each, SAMPLES (default 1)
# samples per pixel on both sides; the two alternate in every round (the host is noisy), each timed right after an
# untimed run of its own; prints every round, the medians and the ratio glref / facet per model. Where f3d and Xvfb
# are installed, f3d's offscreen render of the same file (--output, on Mesa in an Xvfb started once) is a third
# column.
set -euo pipefail
facet=$(realpath "$1")
glref=$(realpath "$2")
rounds=${3:-5}
samples=${4:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Two generated UV spheres: a 200,704-triangle OBJ and an 870,400-triangle ASCII PLY.
python3 "$(dirname "$0")/make_spheres.py" "$work"

f3d_display=
if command -v f3d >/dev/null && command -v Xvfb >/dev/null; then
  Xvfb :97 -screen 0 1920x1080x24 -nolisten tcp >/dev/null 2>&1 &
  xvfb=$!
  trap 'kill $xvfb 2>/dev/null; rm -rf "$work"' EXIT
  f3d_display=:97
  sleep 1
fi

ms() { local start end; start=$(date +%s%N); "$@" >/dev/null 2>&1; end=$(date +%s%N); echo $(((end - start) / 1000)); }
median() { sort -n | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
for model in /usr/share/assimp/models/OBJ/WusonOBJ.obj "$work/sphere200k.obj" "$work/sphere870k.ply"; do
  f=() g=() d=()
  echo "### $(basename "$model")"
  printf '%-6s %12s %12s %8s %12s\n' round "facet (ms)" "glref (ms)" ratio "f3d (ms)"
  for r in $(seq "$rounds"); do
    # The same sample count on both sides: the same job.
    # Each program runs once untimed right before its timed run, so each is timed in the state that a second run
    # (a script's loop, a service) meets, and none pays for the idle host that the one before it left behind: on
    # this virtual machine a process started after a second of idleness can take twice as long. The order of the
    # two alternates from round to round.
    run_facet() {
      ms "$facet" render "$model" --output "$work/f.png" --resolution 1920,1080 --threads 2 --samples "$samples"
    }
    run_glref() {
      ms "$glref" --mesh "$model" --warmup 0 --frames 1 --threads 2 --resolution 1920,1080 --samples "$samples" \
        --png "$work/g.png"
    }
    if [ $((r % 2)) = 1 ]; then
      run_facet >/dev/null; a=$(run_facet); run_glref >/dev/null; b=$(run_glref)
    else
      run_glref >/dev/null; b=$(run_glref); run_facet >/dev/null; a=$(run_facet)
    fi
    c=0
    if [ -n "$f3d_display" ]; then
      DISPLAY=$f3d_display ms f3d "$model" --output="$work/d.png" --resolution=1920,1080 >/dev/null
      c=$(DISPLAY=$f3d_display ms f3d "$model" --output="$work/d.png" --resolution=1920,1080)
    fi
    f+=("$a") g+=("$b") d+=("$c")
    printf '%-6s %12.1f %12.1f %8.2f %12.1f\n' "$r" "$(echo "$a / 1000" | bc -l)" "$(echo "$b / 1000" | bc -l)" \
      "$(echo "$b / $a" | bc -l)" "$(echo "$c / 1000" | bc -l)"
  done
  mf=$(printf '%s\n' "${f[@]}" | median) mg=$(printf '%s\n' "${g[@]}" | median)
  md=$(printf '%s\n' "${d[@]}" | median)
  printf '%-6s %12.1f %12.1f %8.2f %12.1f\n' median "$(echo "$mf / 1000" | bc -l)" "$(echo "$mg / 1000" | bc -l)" \
    "$(echo "$mg / $mf" | bc -l)" "$(echo "$md / 1000" | bc -l)"
done
