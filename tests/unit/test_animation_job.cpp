// test_animation_job.cpp - jobs of many frames: a demo's moving scene and a turntable, written as frames or a GIF.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/demo_scenes.hpp"
#include "facet/image_io.hpp"
#include "facet/render_job.hpp"
#include "support/scratch_dir.hpp"

namespace facet::animation_job_tests {
namespace {

RenderJob demo_job(Demo demo, const std::filesystem::path& color) {
  RenderJob job;
  job.demo = demo;
  job.width = job.height = 48;
  job.samples = 1;
  job.outputs.color = color;
  return job;
}

std::vector<std::uint8_t> png(const std::filesystem::path& path) {
  int w = 0, h = 0;
  return read_png(path, w, h);
}

// Each frame is the demo at its own moment, 1/30 s after the one before: the spinning cube's frame 1 of a run
// from 0.5 s is the single frame at 0.5 + 1/30 s, and differs from frame 0.
TEST(DemoJob, FramesAreTheDemoAtTheirMoments) {
  const std::filesystem::path dir = test::scratch_dir("animation_job");
  Renderer renderer(2);
  RenderJob run = demo_job(Demo::cube, dir / "cube{frame}.png");
  run.time = 0.5;
  run.frames = 3;
  render(run, renderer);
  RenderJob one = demo_job(Demo::cube, dir / "single.png");
  one.time = 0.5 + 1.0 / 30.0;
  render(one, renderer);
  EXPECT_EQ(png(dir / "cube1.png"), png(dir / "single.png"));
  EXPECT_NE(png(dir / "cube0.png"), png(dir / "cube1.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "cube2.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cube3.png"));

  // Depth follows the frames too.
  RenderJob depth = demo_job(Demo::torus, dir / "torus{frame}.png");
  depth.frames = 2;
  depth.outputs.depth = dir / "torus{frame}.npy";
  render(depth, renderer);
  EXPECT_TRUE(std::filesystem::exists(dir / "torus1.npy"));
}

// A GIF holds every frame; the look's settings apply over the demo's own.
TEST(DemoJob, AnAnimationIsOneFileAndTheLookApplies) {
  const std::filesystem::path dir = test::scratch_dir("animation_job");
  Renderer renderer(2);
  RenderJob gif = demo_job(Demo::torus, dir / "torus.gif");
  gif.frames = 4;
  render(gif, renderer);
  EXPECT_GT(std::filesystem::file_size(dir / "torus.gif"), 0u);

  RenderJob red = demo_job(Demo::two_cubes, dir / "red.png");
  red.look.background = glm::vec3(1.0f, 0.0f, 0.0f);
  render(red, renderer);
  const std::vector<std::uint8_t> rgba = png(dir / "red.png");
  EXPECT_EQ(rgba[0], 255);  // the corner shows the background asked for, not the demo's white
  EXPECT_EQ(rgba[1], 0);
}

TEST(DemoJob, RefusesWhatItCannotWrite) {
  const std::filesystem::path dir = test::scratch_dir("animation_job");
  Renderer renderer(1);
  RenderJob job = demo_job(Demo::cube, dir / "refused.png");
  job.frames = 2;  // two frames, one name
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.outputs.color = dir / "refused{frame}.png";
  job.outputs.depth = dir / "refused.npy";  // numbered colour, unnumbered depth
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.outputs.color = dir / "refused.gif";  // a video is colour alone
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.outputs.depth.clear();
  job.frames = kMaxAnimationFrames + 1;
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.frames = 0;
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.frames = 1;
  job.time = std::nan("");
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.time = 1.0;
  job.model = "/usr/share/assimp/models/OBJ/box.obj";  // a demo is not a model file
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.model.clear();
  job.turntable = 8;
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().rfind("refused", 0), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace facet::animation_job_tests
