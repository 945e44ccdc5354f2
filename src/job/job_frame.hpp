// job_frame.hpp - what the render job's parts share: a model or demo made ready to draw, and their timing.
#pragma once

#include <chrono>
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "facet/demo_scenes.hpp"
#include "facet/render_job.hpp"

namespace facet::detail {

// Seconds since it was made or last asked.
class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// A job's model loaded and framed, its view and look, ready to draw.
struct JobFrame {
  View view;
  SceneOptions options;
  glm::vec4 clear{};
  Scene scene;
  // The next frame, when the job asks for motion: the model 1/fps later (or at job.motion's time), seen through the
  // same view (or job.motion's).
  std::optional<Scene> later_scene{};
  View later_view{};
  LaterFrame later() const { return {later_scene ? &*later_scene : nullptr, later_view}; }
};

// Loads job.model (posed at the moment job.animation asks for, if it asks) and frames it as job.camera says; times
// the load and the preparation. With `next_frame` (by default when the job writes motion), poses the model a frame
// later too (JobFrame::later_scene).
JobFrame prepare_job(const RenderJob& job, RenderTimings* timings, bool next_frame);
inline JobFrame prepare_job(const RenderJob& job, RenderTimings* timings = nullptr) {
  return prepare_job(job, timings, !job.outputs.motion.empty());
}
// The same for a mesh already loaded, framed by `framing`; `eye_dome` is eye_dome_lighting_for the mesh as loaded.
JobFrame frame_job(const RenderJob& job, std::shared_ptr<Mesh> mesh, const Framing& framing, float eye_dome);

// A job's model read for its animation (job.animation): the file's nodes, skins and clips, and the clip chosen.
struct MovingModel {
  Model model;
  std::optional<std::size_t> animation;  // into model.animations; none for a file without animations
  double duration = 0;                   // the clip's, in seconds
  double start = 0;                      // job.animation.time clamped to the clip
};
// Reads job.model and chooses its animation. Throws InputError naming the file when it has none of that name or
// index (listing the names it has), or none at all when `required` (a job asking for motion alone does not require
// one: a model that does not move has none); warns when the time lies outside the clip.
MovingModel read_moving_model(const RenderJob& job, bool required = true);
// The scene of the model 1/fps after `seconds` (the clip's last pose past its end), for the motion buffer.
// job.motion's time is for one moment's later frame: prepare_job passes it as `seconds - 1/fps`.
Scene later_scene(const RenderJob& job, const MovingModel& motion, double seconds);
// The model `seconds` into its clip as one world-space mesh.
Mesh posed_mesh(const RenderJob& job, const MovingModel& motion, double seconds);
// frame.options for another view of the same model (a sheet's cell, a turntable's frame): the look's lights follow
// the view (the headlight), and what prepare_job took from the model as loaded (a bare cloud's eye-dome lighting)
// stays.
SceneOptions options_for_view(const RenderJob& job, const JobFrame& frame, const View& view);

// The demo a job names (job.demo), with the look's colour over its own.
DemoModel prepare_demo(const RenderJob& job);
// Frame `frame` of a demo job: the demo at job.time + frame * kDemoSecondsPerFrame, through its own view, the
// job's look over the demo's shading and background.
inline constexpr double kDemoSecondsPerFrame = 1.0 / 30.0;
JobFrame demo_job_frame(const RenderJob& job, const DemoModel& demo, int frame);

// Refuses a job of several images (a sheet, a turntable: `what`, set by `flag`) that asks for more than colour.
void check_colour_only(const RenderJob& job, const char* what, const char* flag);

// The jobs of many frames (animation.cpp): the turntable, a model's animation (with a turntable or without), and a
// demo's frames.
void render_turntable(const RenderJob& job, Renderer& renderer, RenderTimings* timings);
void render_model_animation(const RenderJob& job, Renderer& renderer, RenderTimings* timings);
void render_demo(const RenderJob& job, Renderer& renderer, RenderTimings* timings);

}  // namespace facet::detail
