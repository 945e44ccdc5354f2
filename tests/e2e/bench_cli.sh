#!/usr/bin/env bash
# bench_cli.sh - end-to-end test of `facet bench` (docs/BENCHMARK.md): result line, images, scenes and argument errors.
# Usage: bash tests/e2e/bench_cli.sh <path-to-facet> <scratch-dir>
set -u
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"

facet=${1:?usage: bench_cli.sh <path-to-facet> <scratch-dir>}
scratch=${2:?usage: bench_cli.sh <path-to-facet> <scratch-dir>}
wuson=/usr/share/assimp/models/OBJ/WusonOBJ.obj
rm -rf "$scratch"
mkdir -p "$scratch"

# json_check JSON KEY=VALUE...: every KEY has exactly VALUE (numbers and strings compared as text); prints problems.
json_check() {
  python3 - "$@" <<'EOF'
import json, sys
try:
    obj = json.loads(sys.argv[1])
except ValueError as e:
    print(f"not JSON: {e}"); sys.exit(1)
problems = []
for want in sys.argv[2:]:
    key, value = want.split("=", 1)
    if key not in obj:
        problems.append(f"missing key {key}")
    elif str(obj[key]) != value:
        problems.append(f"{key} is {obj[key]!r}, expected {value}")
for key in ("renderer", "threads", "median_ms", "min_ms", "max_ms"):
    if key not in obj:
        problems.append(f"missing key {key}")
for key in ("median_ms", "min_ms", "max_ms"):
    if key in obj and not (isinstance(obj[key], (int, float)) and obj[key] >= 0):
        problems.append(f"{key} is not a non-negative number")
if all(k in obj for k in ("min_ms", "median_ms", "max_ms")) and not obj["min_ms"] <= obj["median_ms"] <= obj["max_ms"]:
    problems.append("expected min_ms <= median_ms <= max_ms")
print("; ".join(problems))
sys.exit(1 if problems else 0)
EOF
}

# png_size FILE: prints "W H" from the IHDR chunk.
png_size() {
  python3 - "$1" <<'EOF'
import struct, sys
data = open(sys.argv[1], "rb").read(24)
assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR", "not a PNG"
print(*struct.unpack(">II", data[16:24]))
EOF
}

# npy_check FILE W H: version 1.0 '<f4' (H, W) C order, all values in [0, 1], some < 1 and the corner at 1.0.
npy_check() {
  python3 - "$@" <<'EOF'
import ast, struct, sys
path, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
data = open(path, "rb").read()
assert data[:8] == b"\x93NUMPY\x01\x00", "bad magic"
n = struct.unpack("<H", data[8:10])[0]
header = ast.literal_eval(data[10:10 + n].decode("latin1"))
assert header == {"descr": "<f4", "fortran_order": False, "shape": (h, w)}, f"header {header}"
assert (10 + n) % 64 == 0, "data does not start at a multiple of 64"
values = struct.unpack(f"<{w * h}f", data[10 + n:])
assert all(0.0 <= v <= 1.0 for v in values), "depth outside [0, 1]"
assert values[0] == 1.0, "top-left corner should be empty (1.0)"
assert any(v < 1.0 for v in values), "nothing drawn"
EOF
}

# run_ok NAME JSON_CHECKS... -- ARGS...: runs `facet bench ARGS --json`, expects status 0 and one '{' line.
run_ok() {
  local name=$1 checks=() out status lines problems
  shift
  while [ "$1" != "--" ]; do checks+=("$1"); shift; done
  shift
  out=$("$facet" bench "$@" --json 2>"$scratch/stderr.txt")
  status=$?
  if [ $status -ne 0 ]; then bad "$name" "exit status $status: $(head -n 3 "$scratch/stderr.txt")"; return 1; fi
  lines=$(grep -c '^{' <<<"$out")
  if [ "$lines" -ne 1 ]; then bad "$name" "expected one result line starting with '{', got $lines"; return 1; fi
  if problems=$(json_check "$(grep '^{' <<<"$out")" "${checks[@]}"); then ok "$name"
  else bad "$name" "$problems"; return 1; fi
}

# run_bad NAME ARGS...: expects status 2, exactly one stderr line 'facet: error: ...', no result line and no files.
# The image flags go first, so ARGS may end in a flag that lacks its value.
run_bad() {
  local name=$1 dir out status
  shift
  dir=$scratch/bad-$passed-$failed
  mkdir -p "$dir"
  out=$("$facet" bench --json --png "$dir/out.png" --depth "$dir/out.npy" "$@" 2>"$dir/stderr.txt")
  status=$?
  local err_lines
  err_lines=$(wc -l <"$dir/stderr.txt")
  if [ $status -ne 2 ]; then bad "$name" "exit status $status, expected 2"
  elif [ "$err_lines" -ne 1 ]; then bad "$name" "expected one stderr line, got $err_lines"
  elif ! grep -q '^facet: error: ' "$dir/stderr.txt"; then bad "$name" "stderr: $(cat "$dir/stderr.txt")"
  elif grep -q '^{' <<<"$out"; then bad "$name" "printed a result line"
  elif [ -e "$dir/out.png" ] || [ -e "$dir/out.npy" ]; then bad "$name" "wrote a file"
  else ok "$name"; fi
}

# --- the sphere, with both image outputs ---
png=$scratch/sphere16.png npy=$scratch/sphere16.npy
if run_ok "sphere:16 result line" scene=sphere:16 triangles=480 width=64 height=48 warmup=1 frames=2 threads=2 -- \
  --sphere 16 --resolution 64,48 --frames 2 --warmup 1 --threads 2 --png "$png" --depth "$npy"; then
  size=$(png_size "$png" 2>&1)
  if [ "$size" = "64 48" ]; then ok "sphere:16 png is 64x48"; else bad "sphere:16 png" "size '$size'"; fi
  if err=$(npy_check "$npy" 64 48 2>&1); then ok "sphere:16 depth .npy"; else bad "sphere:16 depth .npy" "$err"; fi
fi
# The image must not depend on the thread count (tiles see their triangles in draw order).
run_ok "sphere:16 single-threaded" threads=0 -- --sphere 16 --resolution 64,48 --frames 1 --warmup 0 --threads 0 \
  --png "$scratch/sphere16-t0.png" &&
  { cmp -s "$png" "$scratch/sphere16-t0.png" && ok "sphere:16 same image with --threads 0" ||
    bad "sphere:16 same image with --threads 0"; }
# A repeated flag takes its last value (compare.sh appends its own --warmup/--frames).
run_ok "repeated flags take the last value" frames=3 warmup=0 width=32 height=20 -- \
  --sphere 8 --frames 1 --resolution 64,48 --warmup 2 --frames 3 --warmup 0 --resolution 32,20

# --- multisampling: the result line names the samples, and the image is the same at any thread count ---
if run_ok "sphere:16 with 4 samples" scene=sphere:16 samples=4 -- --sphere 16 --resolution 64,48 --frames 1 \
     --warmup 0 --samples 4 --threads 2 --png "$scratch/sphere16-s4.png" &&
   run_ok "sphere:16 with 4 samples, one thread" samples=4 -- --sphere 16 --resolution 64,48 --frames 1 --warmup 0 \
     --samples 4 --threads 1 --png "$scratch/sphere16-s4-t1.png"; then
  cmp -s "$scratch/sphere16-s4.png" "$scratch/sphere16-s4-t1.png" && ok "4 samples: same image on 1 and 2 threads" ||
    bad "4 samples: same image on 1 and 2 threads"
  cmp -s "$scratch/sphere16-s4.png" "$png" && bad "4 samples differ from 1" "the images are equal" ||
    ok "4 samples differ from 1"
fi

# --- the quads: both orders draw the same picture ---
if run_ok "quads:4:b2f result line" scene=quads:4:b2f triangles=8 width=96 height=54 -- \
     --quads 4 --resolution 96,54 --frames 1 --warmup 0 --png "$scratch/quads-b2f.png" &&
   run_ok "quads:4:f2b result line" scene=quads:4:f2b triangles=8 -- \
     --quads 4 --order f2b --resolution 96,54 --frames 1 --warmup 0 --png "$scratch/quads-f2b.png"; then
  if cmp -s "$scratch/quads-b2f.png" "$scratch/quads-f2b.png"; then ok "quads b2f and f2b images are equal"
  else bad "quads b2f and f2b images are equal"; fi
fi

# --- a mesh (assimp-testmodels) ---
if [ -f "$wuson" ]; then
  run_ok "mesh:WusonOBJ.obj result line" scene=mesh:WusonOBJ.obj triangles=3732 width=80 height=60 -- \
    --mesh "$wuson" --resolution 80,60 --frames 1 --warmup 0 --png "$scratch/wuson.png" &&
    { [ "$(png_size "$scratch/wuson.png" 2>&1)" = "80 60" ] && ok "mesh png is 80x60" || bad "mesh png is 80x60"; }
else
  echo "skip mesh:WusonOBJ.obj ($wuson not installed; apt-get install assimp-testmodels)"
fi

# --- human-readable output and --help ---
out=$("$facet" bench --sphere 4 --resolution 16,16 --frames 1 --warmup 0 2>/dev/null)
if [ $? -eq 0 ] && [ -n "$out" ] && ! grep -q '^{' <<<"$out"; then ok "without --json: a text line"
else bad "without --json: a text line" "'$out'"; fi
if "$facet" bench --help | grep -q -- '--sphere'; then ok "--help lists the flags"
else bad "--help lists the flags"; fi

# --- bad arguments: status 2, one line on stderr, nothing written ---
run_bad "unknown flag" --sphere 16 --frobnicate
run_bad "--order without --quads" --sphere 16 --order f2b
run_bad "two scenes" --sphere 16 --quads 4
run_bad "no scene" --resolution 64,48
run_bad "--sphere 2 is out of range" --sphere 2
run_bad "--sphere not a number" --sphere 1x
run_bad "--resolution 0,5" --sphere 16 --resolution 0,5
run_bad "--resolution without a comma" --sphere 16 --resolution 64
# "isa" names the CPU level that ran: never one this CPU lacks, and under QEMU exactly the level of the CPU it
# emulates: Haswell's AVX2, Nehalem's SSE4.2 and the baseline of qemu64.
isa_of() { grep -o '"isa":"[a-z0-9]*"' <<<"$1" | cut -d'"' -f4; }
rank() { case $1 in baseline) echo 0 ;; sse4) echo 1 ;; avx2) echo 2 ;; avx512) echo 3 ;; *) echo 9 ;; esac; }
bench_isa() { isa_of "$("$@" bench --sphere 8 --resolution 32,24 --frames 1 --warmup 0 --threads 1 --json 2>/dev/null)"; }
native=$(bench_isa "$facet")
case $native in
  avx512) grep -qw avx512f /proc/cpuinfo && ok "isa: avx512 on a CPU with AVX-512" || bad "isa" "avx512 without AVX-512" ;;
  avx2) grep -qw avx2 /proc/cpuinfo && ok "isa: avx2 on a CPU with AVX2" || bad "isa" "avx2 without AVX2" ;;
  sse4) grep -qw sse4_2 /proc/cpuinfo && ok "isa: sse4 on a CPU with SSE4.2" || bad "isa" "sse4 without SSE4.2" ;;
  baseline) ok "isa: baseline" ;;
  *) bad "isa" "unexpected level '$native'" ;;
esac
# FACET_CPU caps the level: each name runs that level, or the CPU's best where that is lower.
for level in avx512 avx2 sse4 baseline; do
  want=$level
  [ "$(rank "$level")" -gt "$(rank "$native")" ] && want=$native
  got=$(FACET_CPU=$level bench_isa "$facet")
  [ "$got" = "$want" ] && ok "FACET_CPU=$level runs $got" || bad "FACET_CPU=$level" "ran '$got', not $want"
done
if FACET_CPU=avx9 "$facet" bench --sphere 8 --resolution 32,24 --frames 1 --warmup 0 >"$scratch/cpu.out" \
  2>"$scratch/cpu.err"; then
  bad "FACET_CPU=avx9" "accepted"
elif [ "$(wc -l <"$scratch/cpu.err")" = 1 ] && grep -q "FACET_CPU=avx9: not a CPU level" "$scratch/cpu.err"; then
  ok "FACET_CPU=avx9: $(cat "$scratch/cpu.err")"
else
  bad "FACET_CPU=avx9" "$(head -n 3 "$scratch/cpu.err")"
fi
# Under QEMU the level follows the emulated CPU, up to the build's own: a build without dispatch (native "baseline"
# on a CPU with SSE4.2) runs the baseline everywhere. A sanitizer's runtime cannot start under qemu-user, so the
# sanitized build checks the native level only; the release build makes these checks.
if [ -n "${FACET_E2E_SANITIZED:-}" ]; then
  :
elif command -v qemu-x86_64 >/dev/null; then
  for cpu in "Haswell,-pcid,-x2apic,-tsc-deadline,-hle,-invpcid,-rtm avx2" "Nehalem sse4" "qemu64 baseline"; do
    read -r model level <<<"$cpu"
    [ "$native" = baseline ] && level=baseline
    got=$(bench_isa qemu-x86_64 -cpu "$model" "$facet")
    [ "$got" = "$level" ] && ok "isa under QEMU's ${model%%,*}: $got" || bad "isa under QEMU's ${model%%,*}" "got '$got', not $level"
  done
else
  bad "isa under QEMU" "qemu-x86_64 is missing: scripts/deps.sh installs qemu-user"
fi

run_bad "--frames 0" --sphere 16 --frames 0
run_bad "--warmup -1" --sphere 16 --warmup -1
run_bad "--threads -1" --sphere 16 --threads -1
run_bad "--scale 0" --sphere 16 --scale 0
run_bad "--order sideways" --quads 4 --order sideways
run_bad "--samples 3" --sphere 16 --samples 3
run_bad "--samples 16" --sphere 16 --samples 16
run_bad "missing value" --sphere
run_bad "missing mesh file" --mesh "$scratch/no-such-mesh.obj"
printf '# nothing\nvn 0 0 1\n' >"$scratch/no-faces.obj"
run_bad "mesh without triangles or points" --mesh "$scratch/no-faces.obj"
printf 'v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n' >"$scratch/coincident.obj"
run_bad "mesh whose vertices all coincide" --mesh "$scratch/coincident.obj"

finish
