#!/usr/bin/env bash
# perf.sh - reproduces docs/PERFORMANCE.md: facet against llvmpipe per scene, thread scaling, memory, micro-benchmarks.
# Usage: scripts/perf.sh [ROUNDS]   (default 3). The OpenGL reference, glref, is built from bench/glref/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
rounds=${1:-3}
scripts/deps.sh f3d  # f3d (VTK, on Mesa under Xvfb) for the whole-process table
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

scenes=("--sphere 224" "--sphere 707" "--sphere 1414" "--quads 64 --order b2f" "--quads 64 --order f2b"
        "--mesh /usr/share/assimp/models/OBJ/WusonOBJ.obj")

echo "## facet against llvmpipe, 2 threads each ($(date -u +%F), $(nproc) CPUs)"
for s in "${scenes[@]}"; do
  # shellcheck disable=SC2086  # the scene flags are meant to split
  ROUNDS=$rounds bench/compare_gl.sh build/tools/facet build/bench/glref build/compare_gl $s --threads 2
done

echo "## every CPU level (FACET_CPU) against llvmpipe, 2 threads each"
bash bench/cpu_levels.sh build/tools/facet build/bench/glref "$rounds"

echo "## a 1M-point cloud against sphere:707, 2 threads"
bash bench/points.sh build/tools/facet "$rounds"

echo "## 4x multisampling against llvmpipe's, 2 threads each"
for s in "--sphere 224" "--sphere 707" "--quads 64 --order f2b" "--mesh /usr/share/assimp/models/OBJ/WusonOBJ.obj"; do
  # shellcheck disable=SC2086
  ROUNDS=$rounds bench/compare_gl.sh build/tools/facet build/bench/glref build/compare_gl $s --threads 2 --samples 4
done
echo "## cost of 4 samples against 1, sphere:224 (median ms of 30 frames, alternated)"
for ((r = 1; r <= rounds; r++)); do
  for n in 1 4; do
    ms=$(./build/tools/facet bench --sphere 224 --threads 2 --samples $n --json | sed -n -E 's/.*"median_ms":([0-9.]+).*/\1/p')
    echo "round $r samples=$n median_ms=$ms"
  done
done

echo "## thread scaling (median ms of 30 frames)"
for s in "--sphere 707" "--quads 64 --order b2f"; do
  for t in 1 2; do
    # shellcheck disable=SC2086
    ms=$(./build/tools/facet bench $s --threads $t --json | sed -n -E 's/.*"median_ms":([0-9.]+).*/\1/p')
    echo "$s threads=$t median_ms=$ms"
  done
done

echo "## peak memory, --sphere 1414, 2 threads"
/usr/bin/time -v ./build/tools/facet bench --sphere 1414 --threads 2 --frames 5 2>&1 | grep -E "Maximum resident|median"

echo "## micro-benchmarks"
build/bench/facet_microbench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

echo "## loading, facet against Assimp"
build/bench/facet_loader_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

echo "## PNG writing, facet against stb_image_write"
build/bench/facet_image_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

echo "## Python against the C++ library"
PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py build 5

echo "## thumbnails: one facet batch against one facet render process each"
bash bench/batch_bench.sh build/tools/facet 3 600
echo "## a batch's peak memory against its job count, up to 100,000 jobs"
bash bench/batch_memory.sh build/tools/facet 100000

echo "## thumbnails: facet thumbnail, in and out of bubblewrap, against f3d's thumbnailer command"
bash bench/thumbnail.sh build/tools/facet "$rounds"

echo "## animation: posing 100k vertices, and a clip to MP4 as a whole process"
build/bench/facet_animation_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
bash bench/animation.sh build/tools/facet "$rounds"
echo
echo "## stock shaders against the benchmark shader, sphere:224"
build/bench/facet_shader_rate_bench --benchmark_repetitions=7 --benchmark_enable_random_interleaving=true \
  --benchmark_report_aggregates_only=true

echo "## the browser page in headless Chromium, 800x600"
bash bench/web_fps.sh "$rounds" 5

echo "## whole processes: facet render against glref (load, draw, write the PNG), every round"
bash bench/whole_process.sh build/tools/facet build/bench/glref "$rounds" 1
bash bench/whole_process.sh build/tools/facet build/bench/glref "$rounds" 4
