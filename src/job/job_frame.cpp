// job_frame.cpp - a job's scene made ready to draw: a model file loaded and framed, or a demo at a moment.
#include "job/job_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "facet/demo_scenes.hpp"
#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "facet/warnings.hpp"

namespace facet::detail {

namespace {

void check_resolution(const RenderJob& job) {
  if (job.width < 1 || job.height < 1 || job.width > kMaxDimension || job.height > kMaxDimension)
    throw std::invalid_argument("resolution: width and height must lie in 1.." + std::to_string(kMaxDimension));
}

// Whether the mesh has points or splats, or a triangle that spans an area (a model of collinear or coincident corners
// draws no pixel).
bool drawable(const Mesh& mesh) {
  if (!mesh.points.empty() || mesh.splats) return true;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
    if (glm::length(glm::cross(b - a, c - a)) > 0.0f) return true;
  }
  return false;
}

}  // namespace

MovingModel read_moving_model(const RenderJob& job, bool required) {
  const std::string source = job.model.string();
  MovingModel out;
  out.model = read_model(job.model, job.load);
  const std::vector<Animation>& clips = out.model.animations;
  if (clips.empty() && !required && job.animation.name.empty()) return out;
  const std::size_t found = animation_named(clips, job.animation.name, source);
  out.animation = found;
  out.duration = clips[found].duration();
  const double time = job.animation.time.value_or(0.0);
  if (!std::isfinite(time)) throw std::invalid_argument("time: must be a finite number of seconds");
  out.start = std::clamp(time, 0.0, out.duration);
  if (out.start != time) {
    char text[160];
    std::snprintf(text, sizeof text, "%g s lies outside the animation (0 to %g s); drawing %g s", time, out.duration,
                  out.start);
    warn(source + ": " + text);
  }
  return out;
}

Mesh posed_mesh(const RenderJob& job, const MovingModel& motion, double seconds) {
  const std::string source = job.model.string();
  return flatten(pose(motion.model, motion.animation, seconds, source, job.load.threads), source);
}

Scene later_scene(const RenderJob& job, const MovingModel& motion, double seconds) {
  Scene scene;
  scene.add(
      Instance{std::make_shared<Mesh>(posed_mesh(job, motion, seconds + 1.0 / job.animation.fps)), glm::mat4(1.0f)});
  return scene;
}

JobFrame prepare_job(const RenderJob& job, RenderTimings* timings, bool next_frame) {
  check_resolution(job);
  Stopwatch clock;
  // The physically based look's environment is prefiltered once per process (a few milliseconds of the first
  // frame): on another thread while the model loads, so that a single render or thumbnail does not wait for it.
  std::future<std::shared_ptr<const Environment>> environment;
  if ((!job.look.shading || *job.look.shading == Shading::automatic) && !job.look.ambient)
    environment = std::async(std::launch::async, [&job] { return environment_for(job.look, job.camera.up); });
  // A job asking for motion reads the model as it reads it for an animation, and poses it a frame later too.
  std::optional<MovingModel> motion;
  if (job.animation.any() || next_frame) motion.emplace(read_moving_model(job, job.animation.any()));
  auto mesh =
      std::make_shared<Mesh>(motion ? posed_mesh(job, *motion, motion->start) : load_model(job.model, job.load));
  // Taken from the model as loaded: a bare cloud keeps eye-dome lighting when a colour map colours it.
  const float eye_dome = eye_dome_lighting_for(job.look, *mesh);
  apply_look_color(*mesh, job.look);
  apply_color_map(*mesh, job.look, job.camera.up);
  if (!drawable(*mesh)) throw InputError(job.model.string(), "every triangle has zero area: nothing to draw");
  if (environment.valid()) environment.get();  // its errors (an unreadable file) after the model's
  if (timings) timings->load = clock.lap();
  const Framing framing = framing_of(*mesh, job.model.string());
  JobFrame frame = frame_job(job, mesh, framing, eye_dome);
  if (next_frame) {
    const double fps = job.animation.fps;
    frame.later_scene.emplace(
        later_scene(job, *motion, job.motion.time ? *job.motion.time - 1.0 / fps : motion->start));
    frame.later_view = frame.view;
    if (job.camera.file_camera)  // the file's camera a frame later: its node may move it
      frame.later_view =
          file_camera_view(*frame.later_scene->instances()[0].mesh, *job.camera.file_camera, framing,
                           static_cast<float>(job.width) / static_cast<float>(job.height), job.model.string());
    if (job.motion.moves_camera()) {
      if (job.camera.file_camera) throw std::invalid_argument("motion: a file's camera cannot be turned");
      CameraSpec turned = job.camera;
      turned.azimuth_degrees += job.motion.azimuth_degrees;
      turned.elevation_degrees += job.motion.elevation_degrees;
      frame.later_view = make_view(turned, framing, static_cast<float>(job.width) / static_cast<float>(job.height));
    }
  }
  if (timings) timings->prepare = clock.lap();
  return frame;
}

JobFrame frame_job(const RenderJob& job, std::shared_ptr<Mesh> mesh, const Framing& framing, float eye_dome) {
  const float aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  JobFrame frame;
  frame.view = job.camera.file_camera
                   ? file_camera_view(*mesh, *job.camera.file_camera, framing, aspect, job.model.string())
                   : make_view(job.camera, framing, aspect);
  if (job.camera.fill && !job.camera.file_camera) frame.view = fill_image(frame.view, mesh->positions);
  frame.clear = clear_color(job.look, kDefaultBackground);
  frame.options = scene_options(job.look, frame.view.view_from_world, Shading::automatic, glm::vec3(frame.clear),
                                mesh->lights, job.camera.up);
  frame.options.eye_dome_lighting = eye_dome;
  frame.scene.add(Instance{std::move(mesh), glm::mat4(1.0f)});
  return frame;
}

SceneOptions options_for_view(const RenderJob& job, const JobFrame& frame, const View& view) {
  SceneOptions options = scene_options(job.look, view.view_from_world, Shading::automatic, glm::vec3(frame.clear),
                                       frame.scene.instances()[0].mesh->lights, job.camera.up);
  options.eye_dome_lighting = frame.options.eye_dome_lighting;
  return options;
}

// A contact sheet or turntable is a colour output alone, seen through cameras of its own.
DemoModel prepare_demo(const RenderJob& job) {
  check_resolution(job);
  DemoModel demo = make_demo(*job.demo);
  if (job.look.color || job.look.color_map != ColorMap::none) {
    Mesh recoloured = *demo.mesh;
    apply_look_color(recoloured, job.look);
    apply_color_map(recoloured, job.look, UpAxis::pos_y);  // demo models stand on +Y
    demo.mesh = std::make_shared<const Mesh>(std::move(recoloured));
  }
  return demo;
}

JobFrame demo_job_frame(const RenderJob& job, const DemoModel& demo, int frame) {
  const float aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  DemoFrame moment = demo_frame(demo, job.time + frame * kDemoSecondsPerFrame, aspect);
  JobFrame out;
  out.view = moment.view;
  out.clear = clear_color(job.look, demo.background);
  for (Instance& instance : moment.instances) out.scene.add(std::move(instance));
  out.options = scene_options(job.look, out.view.view_from_world, demo.shading, glm::vec3(out.clear));
  return out;
}

}  // namespace facet::detail
