// test_long_run.cpp - 10,000 renders in one process: memory stays flat (built without sanitizers, whose allocators
// keep freed memory on purpose).
#include <cstddef>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "support/scratch_dir.hpp"

namespace facet::long_run_tests {
namespace {

// The resident set of this process in KiB, from /proc/self/statm (pages).
std::size_t resident_kib() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * 4;
}

// A model loaded, drawn and written as PNG 10,000 times with one renderer, as a long batch or service does. After
// the first thousand (allocator and caches warm), the next nine thousand may not grow the process. (The batch
// memory test, tests/e2e/batch_memory.sh, covers textured models and the other formats.)
TEST(LongRun, TenThousandRendersKeepMemoryFlat) {
  const std::filesystem::path dir = test::scratch_dir("long_run");
  RenderJob job;
  job.model = "/usr/share/assimp/models/OBJ/box.obj";
  job.width = job.height = 32;
  job.outputs.color = dir / "frame.png";
  Renderer renderer(1);
  std::size_t warm = 0;
  for (int k = 0; k < 10000; ++k) {
    job.camera.azimuth_degrees = static_cast<float>(k % 360);
    render(job, renderer);
    if (k == 999) warm = resident_kib();
  }
  const std::size_t after = resident_kib();
  EXPECT_LE(after, warm + 1024) << "resident after 1,000 renders: " << warm << " KiB; after 10,000: " << after
                                << " KiB";
  EXPECT_TRUE(std::filesystem::exists(job.outputs.color));
}

}  // namespace
}  // namespace facet::long_run_tests
