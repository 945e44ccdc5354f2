#!/usr/bin/env bash
# errors_cli.sh - bad input and bad usage: one "facet: error:" line on stderr, exit 1 (input) or 2 (usage), no output.
# Usage: errors_cli.sh FACET SCRATCH. Prints one line per case and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
models=/usr/share/assimp/models/OBJ
box=$models/box.obj
mkdir -p "$scratch"
rm -rf "${scratch:?}"/*

# Bad model files.
: >"$scratch/empty.obj"
head -c 4096 /dev/urandom >"$scratch/garbage.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n' >"$scratch/out_of_range.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n' >"$scratch/negative_index.obj"
printf 'v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n' >"$scratch/nan.obj"
printf 'v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n' >"$scratch/inf.obj"
printf 'v 0 0 0\nv 3e38 0 0\nv -3e38 1 0\nf 1 2 3\n' >"$scratch/huge.obj"
printf 'vn 0 0 1\nvt 0 0\n' >"$scratch/no_faces.obj"
printf 'solid x\nendsolid x\n' >"$scratch/empty_solid.stl"
printf 'hello\n' >"$scratch/model.dat"
printf '1 2 3\n4 5\n' >"$scratch/short_row.xyz"
head -c 400 /usr/share/assimp/models/PLY/cube_binary.ply >"$scratch/truncated.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n' \
  >"$scratch/header.ply"
mkdir -p "$scratch/folder.obj" "$scratch/folder.png"

# expect NAME STATUS [-n] FACET-ARGS...: runs facet writing to $scratch/NAME.png (unless the args name an output or
# -n asks for none) and checks the exit status, that stderr is exactly one "facet: error: " line, and that no output file appeared.
expect() {
  local name=$1 want=$2 auto_output=1
  shift 2
  if [ "${1:-}" = -n ]; then auto_output=0; shift; fi
  local out=$scratch/$name.png
  rm -f "$out" "$scratch/$name.npy"
  local args=("$@")
  if [[ $auto_output = 1 && " $* " != *" --output "* && $1 != info ]]; then args+=(--output "$out"); fi
  "$facet" "${args[@]}" >"$scratch/$name.stdout" 2>"$scratch/$name.stderr"
  local status=$?
  local lines
  lines=$(wc -l <"$scratch/$name.stderr")
  local first
  first=$(head -n 1 "$scratch/$name.stderr")
  local problem=""
  [ "$status" -eq "$want" ] || problem="exit status $status, expected $want"
  [ "$lines" -eq 1 ] || problem="$problem; $lines stderr lines"
  [[ $first == "facet: error: "* ]] || problem="$problem; stderr does not start with 'facet: error: '"
  if [ -e "$out" ] || [ -e "$scratch/$name.npy" ] || compgen -G "$scratch/.*.tmp*" >/dev/null; then
    problem="$problem; an output file was left behind"
  fi
  if [ -z "$problem" ]; then
    ok "$name ($status): $first"
  else
    bad "$name" "${problem#; } -- $(tr '\n' '|' <"$scratch/$name.stderr")"
  fi
}

# expect_message NAME TEXT: the error line of the case NAME run just before contains TEXT.
expect_message() {
  if grep -qF -- "$2" "$scratch/$1.stderr"; then
    ok "$1 says: $2"
  else
    bad "$1" "expected '$2' in: $(head -n 1 "$scratch/$1.stderr")"
  fi
}

# Bad input: exit 1.
expect missing_file 1 render "$scratch/does_not_exist.obj"
expect empty_file 1 render "$scratch/empty.obj"
expect garbage 1 render "$scratch/garbage.obj"
expect out_of_range_index 1 render "$scratch/out_of_range.obj"
expect negative_index 1 render "$scratch/negative_index.obj"
expect nan_vertex 1 render "$scratch/nan.obj"
expect inf_vertex 1 render "$scratch/inf.obj"
expect huge_coordinates 1 render "$scratch/huge.obj"
expect no_faces 1 render "$scratch/no_faces.obj"
expect unsupported_format 1 render "$scratch/model.dat"
expect_message unsupported_format \
  "unsupported model format '.dat' (supported: .obj, .ply, .stl, .gltf, .glb, .xyz, .pts, .pcd, .splat and the formats Assimp reads)"
expect xyz_short_row 1 render "$scratch/short_row.xyz"
expect_message xyz_short_row "line 2: 2 numbers where the first point has 3"
expect empty_stl 1 render "$scratch/empty_solid.stl"
expect truncated_ply 1 render "$scratch/truncated.ply"
expect_message truncated_ply "runs past the end of the file"
expect truncated_ply_header 1 info "$scratch/header.ply"
expect_message truncated_ply_header "no 'end_header' line"
expect directory_model 1 render "$scratch/folder.obj"
expect unwritable_output 1 render "$box" --output "$scratch/no/such/folder/out.png"
expect output_is_directory 1 render "$box" --output "$scratch/folder.png"
expect unwritable_depth 1 render "$box" --output "$scratch/unwritable_depth.png" \
  --output-depth "$scratch/no/such/folder/depth.npy"
expect unwritable_camera 1 render "$box" --output "$scratch/unwritable_camera.png" \
  --output-mask "$scratch/unwritable_camera_mask.png" --output-camera "$scratch/no/such/folder/camera.json"
[ ! -e "$scratch/unwritable_camera_mask.png" ] && ok "unwritable_camera left no mask" ||
  bad unwritable_camera "the mask was left behind"
expect info_missing 1 info "$scratch/does_not_exist.obj"
expect info_garbage 1 info "$scratch/garbage.obj"
expect demo_unwritable 1 demo cube --output "$scratch/no/such/folder/cube.png"
# A glTF whose buffer lies outside its folder: refused unless --allow-external-files; a FIFO is never read; and
# the limits on triangles.
mkdir -p "$scratch/inside"
python3 -c 'import struct, sys; sys.stdout.buffer.write(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))' \
  >"$scratch/outside.bin"
printf '%s' '{"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"../outside.bin"}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}' \
  >"$scratch/inside/external.gltf"
expect external_buffer 1 render "$scratch/inside/external.gltf"
if "$facet" render "$scratch/inside/external.gltf" --allow-external-files --resolution 32,32 \
  --output "$scratch/external_allowed.png" 2>/dev/null && [ -s "$scratch/external_allowed.png" ]; then
  ok "external_buffer read with --allow-external-files"
else
  bad external_buffer "not rendered with --allow-external-files"
fi
mkfifo "$scratch/fifo.obj"
expect fifo_model 1 render "$scratch/fifo.obj"
expect_message fifo_model "not a regular file"
expect too_many_triangles 1 render "$box" --max-triangles 5
expect_message too_many_triangles "more than the limit of 5 (--max-triangles)"
expect max_triangles_zero 2 render "$box" --max-triangles 0
printf '0 0 0\n1 0 0\n0 1 0\n0 0 1\n' >"$scratch/four.xyz"
expect too_many_points 1 render "$scratch/four.xyz" --max-points 3
expect_message too_many_points "places 4 points and splats, more than the limit of 3 (--max-points)"
expect max_points_zero 2 render "$scratch/four.xyz" --max-points 0
expect max_texture_size_range 2 render "$box" --max-texture-size 20000
# Environments: missing, not an image, not a format facet reads, lying about their size.
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16000 +X 16000\n' >"$scratch/lying.hdr"
head -c 2000 /dev/urandom >"$scratch/garbage.hdr"
expect hdri_missing 1 render "$box" --hdri "$scratch/nowhere.hdr"
expect_message hdri_missing "nowhere.hdr: no such file"
expect hdri_garbage 1 render "$box" --hdri "$scratch/garbage.hdr"
expect hdri_lying 1 render "$box" --hdri "$scratch/lying.hdr"
expect_message hdri_lying "more than its"
expect hdri_png 1 render "$box" --hdri "$scratch/header.ply"
expect_message hdri_png "an environment must be a Radiance .hdr or an OpenEXR .exr file"

# Bad usage: exit 2.
expect no_command 2 -n
expect unknown_command 2 -n paint "$box"
expect unknown_flag 2 render "$box" --bogus
expect missing_model 2 render
expect missing_output 2 -n render "$box" --output-depth "$scratch/missing_output.npy"
expect resolution_zero 2 render "$box" --resolution 0,10
expect resolution_text 2 render "$box" --resolution abc
expect resolution_one_number 2 render "$box" --resolution 640
expect resolution_too_big 2 render "$box" --resolution 100000,10
expect resolution_negative 2 render "$box" --resolution=-5,10
expect resolution_fraction 2 render "$box" --resolution 64.5,48
expect samples_three 2 render "$box" --samples 3
expect tone_mapping_unknown 2 render "$box" --tone-mapping filmic
expect exposure_negative 2 render "$box" --exposure=-1
expect exposure_text 2 render "$box" --exposure bright
expect hdri_blur_range 2 render "$box" --hdri-background --hdri-blur 2
expect samples_zero 2 render "$box" --samples 0
expect demo_samples_sixteen 2 demo cube --samples 16
expect position_two_numbers 2 render "$box" --camera-position 1,2
expect camera_index_none 2 render "$box" --camera-index 0
expect several_models_one_name 2 render "$box" "$box" --output "$scratch/several_models_one_name.png"
expect_message several_models_one_name "several models need {model}, {stem} or {n}"
expect same_name_twice 2 render "$box" "$box" --output "$scratch/{stem}.png"
expect_message same_name_twice "would both write"
expect ids_of_wireframe 2 render "$box" --wireframe --output-ids "$scratch/ids_of_wireframe.npy"
expect position_text 2 render "$box" --camera-position 1,2,x
expect position_nan 2 render "$box" --camera-position 1,nan,3
expect focal_point_empty 2 render "$box" --camera-focal-point ""
expect view_angle_range 2 render "$box" --camera-view-angle 200
expect near_text 2 render "$box" --near abc
expect near_after_far 2 render "$box" --near 5 --far 1
expect perspective_near_zero 2 render "$box" --near 0
expect eye_at_focal_point 2 render "$box" --camera-position 0,0,0 --camera-focal-point 0,0,0
expect frustum_three_numbers 2 render "$box" --projection frustum --frustum 1,2,3
expect frustum_empty_window 2 render "$box" --projection frustum --frustum 1,1,-1,1
expect bad_projection 2 render "$box" --projection fisheye
expect bad_shading 2 render "$box" --shading toon
expect bad_culling 2 render "$box" --culling sideways
expect bad_up 2 render "$box" --up +W
expect color_out_of_range 2 render "$box" --color 2,0,0
expect background_text 2 render "$box" --background-color red
expect zero_light 2 render "$box" --light-direction 0,0,0
expect threads_negative 2 render "$box" --threads=-1
expect same_depth_and_color 2 render "$box" --output "$scratch/same.png" --output-depth "$scratch/same.png"
expect same_mask_and_color 2 render "$box" --output "$scratch/same2.png" --output-mask "$scratch/same2.png"
expect demo_unknown 2 demo teapot
expect demo_frames_without_pattern 2 demo cube --frames 3
expect demo_frames_zero 2 demo cube --frames 0
expect demo_time_text 2 demo cube --time soon
expect oblique_scale_range 2 render "$box" --projection oblique --oblique-scale 20
expect threads_text 2 render "$box" --threads many
expect frames_text 2 demo cube --frames x --output "$scratch/frames_text_{frame}.png"

finish
