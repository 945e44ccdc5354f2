// animation.cpp - jobs of many frames: a turntable's turning camera and a demo's moving scene, drawn by one loop.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/demo_scenes.hpp"
#include "facet/image_io.hpp"
#include "facet/output_template.hpp"
#include "facet/render_job.hpp"
#include "job/job_frame.hpp"

namespace facet::detail {

namespace {

// One frame as an animation's source makes it: what to draw, through which view, how.
struct AnimationFrame {
  Scene* scene;  // the source's
  View view;
  SceneOptions options;
  LaterFrame later{};  // the next frame, for the motion buffer
};
using AnimationSource = std::function<AnimationFrame(int frame)>;

// Whether the job's colour output is one GIF or video of every frame, rather than PNG frames named with {frame}.
bool is_video(const RenderJob& job) {
  return is_animation_path(job.outputs.color) && !template_has(job.outputs.color.string(), "frame");
}

// A video holds every frame in memory until it is encoded: at most kMaxAnimationFrames, and 2^30 pixels in all.
void check_video_size(const RenderJob& job, int frames, const char* flag) {
  if (frames > kMaxAnimationFrames)
    throw std::invalid_argument(std::string(flag) + ": at most " + std::to_string(kMaxAnimationFrames) + " frames");
  const std::uint64_t pixels = static_cast<std::uint64_t>(job.width) * job.height * frames;
  if (is_video(job) && pixels > (std::uint64_t{1} << 30))
    throw std::invalid_argument(std::string(flag) + ": " + std::to_string(frames) + " frames of " +
                                std::to_string(job.width) + "x" + std::to_string(job.height) +
                                " are over 2^30 pixels; use fewer frames or a smaller resolution");
}

// Refuses outputs that cannot hold `frames` frames: a video of more than colour, or of too many pixels; files that
// their names' {frame} does not number.
void check_frame_outputs(const RenderJob& job, int frames, const char* flag) {
  if (is_video(job)) check_colour_only(job, "an animation", flag);
  check_video_size(job, frames, flag);
  if (frames > 1 && !is_video(job))
    for (const std::filesystem::path& path : output_paths(job.outputs))
      if (!template_has(path.string(), "frame"))
        throw std::invalid_argument(path.string() + ": " + std::to_string(frames) +
                                    " frames need {frame} in the name, one file per frame");
}

// A clip is framed by the model at this many moments through it and its start.
constexpr int kFramingMoments = 8;

// Draws frames 0 .. count - 1 of `source` and writes them as the job's outputs say: one GIF or video of them all,
// `seconds_per_frame` apart; else each frame's outputs, their names' {frame} expanded, as soon as it is drawn (a
// failure leaves the frames already written, which a rerun replaces). Times the drawing and the writing.
void draw_frames(const RenderJob& job, int count, double seconds_per_frame, glm::vec4 clear,
                 const AnimationSource& source, Renderer& renderer, RenderTimings* timings) {
  Framebuffer target(job.width, job.height, job.samples);
  target.keep_depth(false);  // draw_buffers keeps it for a frame whose outputs read it
  const bool video = is_video(job);
  std::vector<std::vector<std::uint8_t>> frames;  // a video's, encoded together at the end
  RenderTimings spent;
  Stopwatch clock;
  for (int k = 0; k < count; ++k) {
    const AnimationFrame frame = source(k);
    if (video) {
      renderer.clear(target, clear, 1.0f);
      frame.scene->render(renderer, target, frame.view, frame.options);
      renderer.finish(target);
      frames.push_back(target.rgba8());
      spent.draw += clock.lap();
      continue;
    }
    const TemplateValues values{.frame = k};
    const auto expand = [&](const std::filesystem::path& path) {
      return path.empty() ? path : std::filesystem::path(expand_template(path.string(), values));
    };
    const OutputSpec& o = job.outputs;
    const OutputSpec outputs{.color = expand(o.color),
                             .depth = expand(o.depth),
                             .normal = expand(o.normal),
                             .ids = expand(o.ids),
                             .mask = expand(o.mask),
                             .camera = expand(o.camera),
                             .motion = expand(o.motion)};
    RenderTimings t;
    draw_and_write(renderer, target, *frame.scene, frame.view, frame.options, clear, outputs, &t, &frame.later);
    spent.draw += t.draw;
    spent.write += t.write;
    clock.lap();
  }
  if (video) {
    write_animation(job.outputs.color, job.width, job.height, frames, seconds_per_frame);
    spent.write += clock.lap();
  }
  if (timings) timings->draw = spent.draw, timings->write = spent.write;
}

}  // namespace

void render_turntable(const RenderJob& job, Renderer& renderer, RenderTimings* timings) {
  check_colour_only(job, "a turntable", "turntable");
  check_video_size(job, job.turntable, "turntable");
  JobFrame frame = prepare_job(job, timings);
  const Framing framing = framing_of(*frame.scene.instances()[0].mesh, job.model.string());
  const float aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  const auto turned = [&](int k) {
    CameraSpec camera = job.camera;
    camera.azimuth_degrees += 360.0f * static_cast<float>(k) / static_cast<float>(job.turntable);
    const View view = make_view(camera, framing, aspect);
    return AnimationFrame{&frame.scene, view, options_for_view(job, frame, view)};
  };
  // A whole turn in about 3 s, at no more than 50 frames a second (GIF delays are whole centiseconds).
  draw_frames(job, job.turntable, std::max(0.02, 3.0 / job.turntable), frame.clear, turned, renderer, timings);
}

void render_model_animation(const RenderJob& job, Renderer& renderer, RenderTimings* timings) {
  const AnimationSpec& spec = job.animation;
  if (!job.views.empty()) throw std::invalid_argument("animation: a contact sheet is one image, not an animation");
  if (!(spec.fps >= 1.0 && spec.fps <= kMaxAnimationFps))
    throw std::invalid_argument("fps: must lie in 1.." + std::to_string(static_cast<int>(kMaxAnimationFps)));
  if (spec.frames < 0) throw std::invalid_argument("frames: at least 1, or 0 for the whole clip");
  Stopwatch clock;
  const MovingModel motion = read_moving_model(job);
  // Every frame is 1/fps after the last; a turntable's frames turn the camera once round and loop the clip.
  const int turns = job.turntable;
  const double remaining = motion.duration - motion.start;
  const int count = spec.frames > 0 ? spec.frames
                    : turns > 0     ? turns
                                    : std::max(1, static_cast<int>(std::ceil(remaining * spec.fps - 1e-6)));
  check_frame_outputs(job, count, "frames");
  const auto moment = [&](int k) {
    const double t = motion.start + k / spec.fps;
    return motion.duration > 0.0 && t > motion.duration ? std::fmod(t, motion.duration) : t;
  };
  // Framed once, by the model at moments from the start to the end of the clip, so that the camera holds still.
  std::vector<glm::vec3> corners;
  for (int s = 0; s <= kFramingMoments; ++s) {
    const Bounds b = bounds(posed_mesh(job, motion, motion.start + remaining * s / kFramingMoments));
    corners.insert(corners.end(), {b.min, b.max});
  }
  Mesh hull;
  hull.positions = std::move(corners);
  const Framing framing = framing_of(hull, job.model.string());
  if (timings) timings->load = clock.lap();
  // Each frame's mesh takes the look's colours as a still's does.
  const auto coloured = [&](double seconds) {
    auto mesh = std::make_shared<Mesh>(posed_mesh(job, motion, seconds));
    apply_look_color(*mesh, job.look);
    apply_color_map(*mesh, job.look, job.camera.up);
    return mesh;
  };
  const float eye_dome = eye_dome_lighting_for(job.look, posed_mesh(job, motion, moment(0)));
  std::optional<JobFrame> frame;
  frame.emplace(frame_job(job, coloured(moment(0)), framing, eye_dome));
  const float aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  if (timings) timings->prepare = clock.lap();
  const auto view_of = [&](int k) {
    if (turns == 0 || job.camera.file_camera) return frame->view;
    CameraSpec camera = job.camera;
    camera.azimuth_degrees += 360.0f * static_cast<float>(k) / static_cast<float>(count);
    return make_view(camera, framing, aspect);
  };
  std::optional<Scene> later;  // the next frame's model, for the motion buffer
  const auto posed = [&](int k) {
    // A file's camera is the frame's own: its node may move it.
    if (k > 0) frame.emplace(frame_job(job, coloured(moment(k)), framing, eye_dome));
    const View view = view_of(k);
    View next = view_of(k + 1);
    if (!job.outputs.motion.empty()) {
      later.emplace(later_scene(job, motion, moment(k)));
      if (job.camera.file_camera)
        next =
            file_camera_view(*later->instances()[0].mesh, *job.camera.file_camera, framing, aspect, job.model.string());
    }
    return AnimationFrame{&frame->scene, view, options_for_view(job, *frame, view),
                          LaterFrame{later ? &*later : nullptr, next}};
  };
  draw_frames(job, count, 1.0 / spec.fps, frame->clear, posed, renderer, timings);
}

void render_demo(const RenderJob& job, Renderer& renderer, RenderTimings* timings) {
  if (!job.model.empty()) throw std::invalid_argument("demo: a demo draws its own scene, not " + job.model.string());
  if (!job.views.empty() || job.turntable > 0)
    throw std::invalid_argument("demo: a demo has its own camera and motion: no views or turntable");
  if (job.frames < 1) throw std::invalid_argument("frames: at least 1");
  if (!std::isfinite(job.time)) throw std::invalid_argument("time: must be a finite number of seconds");
  check_frame_outputs(job, job.frames, "frames");
  Stopwatch clock;
  const DemoModel demo = prepare_demo(job);
  std::optional<JobFrame> frame;
  frame.emplace(demo_job_frame(job, demo, 0));
  if (timings) timings->prepare = clock.lap();
  const auto moment = [&](int k) {
    if (k > 0) frame.emplace(demo_job_frame(job, demo, k));
    return AnimationFrame{&frame->scene, frame->view, frame->options};
  };
  draw_frames(job, job.frames, kDemoSecondsPerFrame, frame->clear, moment, renderer, timings);
}

}  // namespace facet::detail
