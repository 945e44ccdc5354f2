#!/usr/bin/env bash
# thumbnail.sh - a 256x256 thumbnail as a file manager makes it: `facet thumbnail` as a whole process, outside and
# inside GNOME's bubblewrap sandbox, against f3d's thumbnailer command (Debian's f3d, on Mesa in an Xvfb started
# once). Usage: bench/thumbnail.sh FACET [ROUNDS]. WusonOBJ, a 2 MB textured GLB and the 870k-triangle ASCII PLY;
# the three alternate in every round, each timed right after an untimed run of its own. Prints every round's ms and
# peak memory (MiB), then the medians and f3d / facet.
set -euo pipefail
facet=$(realpath "$1")
rounds=${2:-5}
work=$(mktemp -d)
here=$(cd "$(dirname "$0")" && pwd)
python3 "$here/make_spheres.py" "$work"
/usr/bin/python3 "$here/make_textured_glb.py" "$work/textured.glb"
Xvfb :96 -screen 0 1280x1024x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$work"' EXIT
sleep 1

# time_of CMD...: "MS MIB" of one run (wall clock, and the peak resident memory of the process /usr/bin/time waits for).
time_of() {
  local start end
  start=$(date +%s%N)
  /usr/bin/time -f %M -o "$work/rss" "$@" >/dev/null 2>&1
  end=$(date +%s%N)
  echo "$(((end - start) / 1000)) $(($(tail -1 "$work/rss") / 1024))"
}
run_facet() { time_of "$facet" thumbnail -s 256 "$1" "$work/f.png"; }
run_bwrap() {
  time_of bwrap --ro-bind /usr /usr --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache --symlink usr/bin /bin \
    --symlink usr/lib /lib --symlink usr/lib64 /lib64 --proc /proc --dev /dev --chdir / --setenv GIO_USE_VFS local \
    --unshare-all --die-with-parent --bind "$work/sandbox" /tmp \
    --ro-bind "$1" "/tmp/gnome-desktop-file-to-thumbnail.${1##*.}" --ro-bind "$facet" /opt/facet/facet \
    /opt/facet/facet thumbnail -s 256 "file:///tmp/gnome-desktop-file-to-thumbnail.${1##*.}" /tmp/t.png
}
run_f3d() {
  DISPLAY=:96 time_of f3d --dry-run -sta --no-background --output="$work/d.png" --resolution=256,256 "$1"
}
median() { sort -n | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

for model in /usr/share/assimp/models/OBJ/WusonOBJ.obj "$work/textured.glb" "$work/sphere870k.ply"; do
  rm -rf "$work/sandbox" && mkdir "$work/sandbox"
  echo "### $(basename "$model") ($(($(stat -c %s "$model") / 1024)) KiB)"
  printf '%-6s %10s %8s %10s %10s %8s %8s\n' round "facet ms" "MiB" "bwrap ms" "f3d ms" "MiB" "f3d/fct"
  fa=() fm=() ba=() da=() dm=()
  for r in $(seq "$rounds"); do
    order=(facet bwrap f3d)
    [ $((r % 3)) = 1 ] && order=(bwrap f3d facet)
    [ $((r % 3)) = 2 ] && order=(f3d facet bwrap)
    for who in "${order[@]}"; do
      "run_$who" "$model" >/dev/null
      read -r ms mib < <("run_$who" "$model")
      case $who in facet) f=$ms; fmib=$mib ;; bwrap) b=$ms ;; f3d) d=$ms; dmib=$mib ;; esac
    done
    fa+=("$f") fm+=("$fmib") ba+=("$b") da+=("$d") dm+=("$dmib")
    printf '%-6s %10.1f %8s %10.1f %10.1f %8s %8.1f\n' "$r" "$(echo "$f / 1000" | bc -l)" "$fmib" \
      "$(echo "$b / 1000" | bc -l)" "$(echo "$d / 1000" | bc -l)" "$dmib" "$(echo "$d / $f" | bc -l)"
  done
  mf=$(printf '%s\n' "${fa[@]}" | median) mb=$(printf '%s\n' "${ba[@]}" | median)
  md=$(printf '%s\n' "${da[@]}" | median)
  printf '%-6s %10.1f %8s %10.1f %10.1f %8s %8.1f   bwrap/facet %.2f\n' median "$(echo "$mf / 1000" | bc -l)" \
    "$(printf '%s\n' "${fm[@]}" | median)" "$(echo "$mb / 1000" | bc -l)" "$(echo "$md / 1000" | bc -l)" \
    "$(printf '%s\n' "${dm[@]}" | median)" "$(echo "$md / $mf" | bc -l)" "$(echo "$mb / $mf" | bc -l)"
done
