#!/usr/bin/env bash
# thumbnailer.sh - `facet thumbnail` as a file manager runs it: inside bubblewrap with GNOME's sandbox arguments,
# on a file of every MIME type the thumbnailer entry lists; its limits; and the installed entry and MIME package.
# Usage: thumbnailer.sh FACET SCRATCH BUILD_DIR
set -uo pipefail
facet=$(realpath "$1")
scratch=$2
build=$3
# shellcheck source=lib/common.bash
source "$(dirname "$0")/lib/common.bash"
models=/usr/share/assimp/models
command -v bwrap >/dev/null || "$(dirname "$0")/../../scripts/deps.sh"
rm -rf "$scratch"
mkdir -p "$scratch/in"

# Point clouds and splats facet writes itself: a text cloud, a PCD file and a .splat scene.
python3 - "$scratch/in" <<'PY'
import math, struct, sys
folder = sys.argv[1]
ring = [(math.cos(t / 40 * math.tau), math.sin(t / 40 * math.tau), z / 10) for t in range(40) for z in range(10)]
with open(f"{folder}/ring.xyz", "w") as f:
    f.writelines(f"{x} {y} {z} 200 {int(z * 250)} 40\n" for x, y, z in ring)
with open(f"{folder}/ring.pts", "w") as f:
    f.write(f"{len(ring)}\n")
    f.writelines(f"{x} {y} {z} 0 200 {int(z * 250)} 40\n" for x, y, z in ring)
with open(f"{folder}/ring.pcd", "w") as f:
    f.write("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
            f"WIDTH {len(ring)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(ring)}\nDATA ascii\n")
    f.writelines(f"{x} {y} {z}\n" for x, y, z in ring)
with open(f"{folder}/ring.splat", "wb") as f:
    for x, y, z in ring:
        f.write(struct.pack("<6f4B4B", x, y, z, 0.05, 0.05, 0.05, 220, int(z * 250), 60, 255, 255, 128, 128, 128))
PY

# One file of each type the entry lists, by its glob's extension.
declare -A sample=(
  [glb]=$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb [gltf]=$models/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf
  [obj]=$models/OBJ/WusonOBJ.obj [stl]=$models/STL/Spider_binary.stl [3mf]=$models/3MF/box.3mf
  [3ds]=$models/3DS/fels.3ds [lwo]=$models/LWO/LWO2/hierarchy.lwo [ply]=$models/PLY/Wuson.ply
  [fbx]=$models/FBX/spider.fbx [dae]=$models/Collada/duck.dae [off]=$models/OFF/Wuson.off
  [pts]=$scratch/in/ring.pts [x3d]=$models/X3D/ComputerKeyboard.x3d [pcd]=$scratch/in/ring.pcd
  [xyz]=$scratch/in/ring.xyz [splat]=$scratch/in/ring.splat)
extensions=$(sed -n 's/^MimeType=//p' "$(dirname "$0")/../../data/facet.thumbnailer" | tr ';' '\n' | grep -c .)
[ "$extensions" -eq 16 ] && ok "the entry lists 16 types, one sample each" ||
  bad "the entry lists $extensions types; the samples cover 16"

# GNOME's thumbnail sandbox (gnome-desktop's thumbnail script): /usr read-only, the output folder as /tmp, the input
# bound read-only beside it under a fixed name with its extension, no namespaces shared, gone with its parent. The
# program is bound into /opt, as the package installs it into /usr/bin.
sandboxed() {  # sandboxed INPUT OUTDIR ARGS...: runs `facet ARGS...` in the sandbox, the input as file:///tmp/input.EXT
  local input=$1 outdir=$2
  shift 2
  bwrap --ro-bind /usr /usr --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache \
    --symlink usr/bin /bin --symlink usr/lib /lib --symlink usr/lib64 /lib64 --symlink usr/sbin /sbin \
    --proc /proc --dev /dev --chdir / --setenv GIO_USE_VFS local --unshare-all --die-with-parent \
    --bind "$outdir" /tmp --ro-bind "$input" "/tmp/gnome-desktop-file-to-thumbnail.${input##*.}" \
    --ro-bind "$facet" /opt/facet/facet /opt/facet/facet "$@"
}

check_thumbnail() {  # check_thumbnail PNG SIZE URI: square RGBA, transparent corner, model drawn, URI recorded
  python3 - "$@" <<'PY'
import sys, zlib, struct
path, size, uri = sys.argv[1], int(sys.argv[2]), sys.argv[3]
data = open(path, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
at, text, idat = 8, {}, b""
while at < len(data):
    n, kind = struct.unpack(">I4s", data[at:at + 8])
    body = data[at + 8:at + 8 + n]
    if kind == b"IHDR": width, height, depth, colour = struct.unpack(">IIBB", body[:10])
    if kind == b"tEXt": key, _, value = body.partition(b"\0"); text[key.decode()] = value.decode("latin-1")
    if kind == b"IDAT": idat += body
    at += 12 + n
assert (width, height, depth, colour) == (size, size, 8, 6), (width, height, depth, colour)
assert text.get("Thumb::URI") == uri, text
assert text.get("Thumb::MTime", "").isdigit(), text
raw, stride, prev, alpha = zlib.decompress(idat), 4 * size, bytearray(4 * size), []
for y in range(size):
    row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    assert raw[y * (stride + 1)] == 2, "facet writes the Up filter"
    row = bytearray((a + b) & 255 for a, b in zip(row, prev))
    alpha += row[3::4]
    prev = row
assert alpha[0] == 0, "the corner is transparent"
covered = sum(a > 0 for a in alpha) / len(alpha)
assert covered > 0.04, f"only {covered:.1%} of the square is drawn"
PY
}

# (bwrap leaves the input's mount point, an empty file, in the output folder: it is the sandbox's, not facet's.)
for ext in "${!sample[@]}"; do
  out=$scratch/out-$ext
  mkdir -p "$out"
  uri=file:///tmp/gnome-desktop-file-to-thumbnail.$ext
  if ! sandboxed "${sample[$ext]}" "$out" thumbnail -s 128 "$uri" /tmp/gnome-desktop-thumbnailer.png \
    2>"$scratch/$ext.err" >/dev/null; then
    bad "$ext thumbnail in the sandbox" "$(tail -1 "$scratch/$ext.err")"
  elif ! msg=$(check_thumbnail "$out/gnome-desktop-thumbnailer.png" 128 "$uri" 2>&1); then
    bad "$ext thumbnail" "$(echo "$msg" | tail -1)"
  elif [ "$(ls -A "$out" | grep -v '^gnome-desktop-file-to-thumbnail')" != gnome-desktop-thumbnailer.png ]; then
    bad "$ext: the sandbox's writable folder holds only the thumbnail" "$(ls -A "$out" | tr '\n' ' ')"
  else
    ok "$ext thumbnail in the sandbox"
  fi
done

# A thumbnailer that shows the model's folder (read-only, at its own path) gets the files the model names: the
# glTF's buffer and image, the OBJ's MTL and texture, and nothing is reported missing.
for model in glTF2/BoxTextured-glTF/BoxTextured.gltf OBJ/spider.obj; do
  folder=$(dirname "$models/$model")
  out=$scratch/folder-$(basename "$model")
  mkdir -p "$out"
  if bwrap --ro-bind /usr /usr --symlink usr/lib /lib --symlink usr/lib64 /lib64 --proc /proc --dev /dev \
    --unshare-all --die-with-parent --bind "$out" /tmp --ro-bind "$folder" "$folder" \
    --ro-bind "$facet" /opt/facet/facet /opt/facet/facet thumbnail "file://$models/$model" /tmp/t.png \
    2>"$out.err" && [ ! -s "$out.err" ] && check_thumbnail "$out/t.png" 256 "file://$models/$model"; then
    ok "$model with its folder: every file it names is read"
  else
    bad "$model with its folder: every file it names is read" "$(head -2 "$out.err")"
  fi
done

# The limits: a file over the size limit, a model not drawn in time, a truncated file. Each ends with status 1,
# one line naming the input, and nothing written.
truncated=$scratch/in/truncated.glb
head -c 900 "${sample[glb]}" >"$truncated"
limit_case() {  # limit_case NAME INPUT EXPECTED_TEXT ARGS...
  local name=$1 input=$2 expected=$3 out=$scratch/limit-$1 status
  shift 3
  mkdir -p "$out"
  sandboxed "$input" "$out" thumbnail "file:///tmp/gnome-desktop-file-to-thumbnail.${input##*.}" /tmp/t.png "$@" \
    >/dev/null 2>"$scratch/$name.err"
  status=$?
  if [ "$status" -ne 1 ]; then bad "$name: status 1" "got $status"
  elif [ "$(wc -l <"$scratch/$name.err")" -ne 1 ] || ! grep -q "^facet: error: .*$expected" "$scratch/$name.err"; then
    bad "$name: one error line saying '$expected'" "$(head -3 "$scratch/$name.err")"
  elif [ -n "$(ls -A "$out" | grep -v '^gnome-desktop-file-to-thumbnail')" ]; then bad "$name: nothing written" "$(ls -A "$out" | tr '\n' ' ')"
  else ok "$name: $(cat "$scratch/$name.err")"
  fi
}
limit_case size "${sample[obj]}" "over the thumbnail limit" --max-input-size 0.1
limit_case time "${sample[ply]}" "no thumbnail within 0.001 s" --time-limit 0.001
limit_case truncated "$truncated" "gnome-desktop-file-to-thumbnail.glb"
if "$facet" thumbnail sftp://host/m.obj "$scratch/r.png" 2>"$scratch/remote.err"; then bad "an sftp:// URI is refused"
elif grep -q "not a local file" "$scratch/remote.err" && [ ! -e "$scratch/r.png" ]; then ok "an sftp:// URI is refused"
else bad "an sftp:// URI is refused" "$(cat "$scratch/remote.err")"
fi

# Installed, the entry and the MIME package land where desktops look, and update-mime-database takes the types in.
prefix=$scratch/prefix
if cmake --install "$build" --prefix "$prefix" --component runtime >"$scratch/install.log" 2>&1 &&
  [ -f "$prefix/share/thumbnailers/facet.thumbnailer" ] && [ -f "$prefix/share/mime/packages/facet.xml" ]; then
  ok "cmake --install puts facet.thumbnailer and the MIME package under share/"
else
  bad "cmake --install puts facet.thumbnailer and the MIME package under share/" "$(tail -2 "$scratch/install.log")"
fi
if update-mime-database "$prefix/share/mime" 2>"$scratch/mime.err" &&
  grep -q "application/vnd.ply:\*.ply" "$prefix/share/mime/globs2" &&
  grep -q "application/x-splat:\*.splat" "$prefix/share/mime/globs2"; then
  ok "update-mime-database reads facet's types"
else
  bad "update-mime-database reads facet's types" "$(cat "$scratch/mime.err")"
fi
finish
