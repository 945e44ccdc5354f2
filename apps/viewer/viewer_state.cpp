// viewer_state.cpp - the viewer's scene, view and options for one frame, from the toggles and the orbit camera.
#include "viewer_state.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <span>
#include <utility>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "facet/projection.hpp"
#include "facet/transform.hpp"

namespace facet::viewer {

Mesh shuffled(const Mesh& mesh, int seed) {
  std::vector<std::size_t> order(mesh.triangle_count());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937 rng(static_cast<std::uint32_t>(seed));
  std::shuffle(order.begin(), order.end(), rng);
  Mesh out = mesh;
  const auto permute = [&](const auto& from, auto& to) {
    if (from.empty()) return;
    for (std::size_t t = 0; t < order.size(); ++t) to[t] = from[order[t]];
  };
  for (std::size_t t = 0; t < order.size(); ++t)
    for (int k = 0; k < 3; ++k) out.indices[3 * t + k] = mesh.indices[3 * order[t] + k];
  permute(mesh.face_colors, out.face_colors);
  permute(mesh.face_materials, out.face_materials);
  permute(mesh.face_ids, out.face_ids);
  permute(mesh.instance_ids, out.instance_ids);
  // The file's face numbers travel with the triangles, so ids still name the faces the file has.
  if (out.face_ids.empty()) {
    out.face_ids.resize(order.size());
    for (std::size_t t = 0; t < order.size(); ++t) out.face_ids[t] = static_cast<std::uint32_t>(order[t]);
  }
  return out;
}

void turn_by(Orbit& orbit, glm::vec2 drag) {
  orbit.azimuth_degrees -= 0.4f * drag.x;
  orbit.elevation_degrees = std::clamp(orbit.elevation_degrees + 0.4f * drag.y, -89.0f, 89.0f);
}

void pan_by(Orbit& orbit, glm::vec2 drag, int height) {
  orbit.pan += glm::vec2(drag.x, -drag.y) * (2.0f / static_cast<float>(std::max(height, 1))) / orbit.zoom;
}

void zoom_by(Orbit& orbit, float wheel_steps) {
  orbit.zoom = std::clamp(orbit.zoom * std::pow(1.1f, wheel_steps), 0.05f, 50.0f);
}

struct Showing::Motion {
  Model model;
  Poser poser;
  double duration = 0.0;
};

Showing Showing::model(const std::string& path, const LoadOptions& load) {
  Showing s;
  s.title_ = std::filesystem::path(path).filename().string();
  Model model = read_model(path, load);
  if (model.animations.empty()) {
    s.mesh_ = std::make_shared<const Mesh>(flatten(at_rest(std::move(model), path, load.threads), path));
  } else {
    const double duration = model.animations.front().duration();
    s.motion_ = std::make_shared<Motion>(Motion{std::move(model), Poser(load.threads), duration});
    s.mesh_ = std::make_shared<const Mesh>(flatten(s.motion_->poser(s.motion_->model, 0, 0.0, path), path));
  }
  s.framing_ = framing_of(*s.mesh_, path);
  return s;
}

Showing Showing::demo(Demo demo) {
  Showing s;
  s.demo_ = make_demo(demo);
  s.mesh_ = s.demo_->mesh;
  s.title_ = std::string("demo ") + demo_name(demo);
  return s;
}

void Showing::rebuild_scene(int shuffles, ColorMap color_map) {
  std::shared_ptr<const Mesh> mesh = mesh_;
  if (color_map != ColorMap::none) {
    Mesh coloured = *mesh_;
    LookSpec look;
    look.color_map = color_map;
    apply_color_map(coloured, look, UpAxis::pos_y);  // models are framed, and demos stand, with +Y up
    mesh = std::make_shared<const Mesh>(std::move(coloured));
  }
  if (shuffles != 0) mesh = std::make_shared<const Mesh>(shuffled(*mesh, shuffles));
  scene_ = Scene();
  const std::size_t instances = demo_ ? demo_frame(*demo_, 0.0, 1.0f).instances.size() : 1;
  for (std::size_t i = 0; i < instances; ++i) scene_.add(Instance{mesh, glm::mat4(1.0f)});
  scene_shuffles_ = shuffles;
  scene_color_map_ = color_map;
}

Showing::Frame Showing::frame(double seconds, float aspect, const Toggles& toggles, const Orbit& orbit,
                              const LookSpec& base) {
  // A model's animation loops; a new moment is a new mesh, and a new scene for it.
  if (motion_ && seconds != posed_at_) {
    const double t = motion_->duration > 0.0 ? std::fmod(std::max(seconds, 0.0), motion_->duration) : 0.0;
    mesh_ = std::make_shared<const Mesh>(flatten(motion_->poser(motion_->model, 0, t, title_), title_));
    posed_at_ = seconds;
    scene_shuffles_ = -1;
  }
  // A model opened under a colour map it cannot take (no intensities) shows its own colours.
  const ColorMap map = supports(toggles.color_map) ? toggles.color_map : ColorMap::none;
  if (scene_shuffles_ != toggles.shuffles || scene_color_map_ != map) rebuild_scene(toggles.shuffles, map);
  LookSpec look = base;
  look.shading = toggles.shading;
  look.wireframe = toggles.wireframe;
  look.edges = toggles.edges && !toggles.wireframe;
  look.depth_test = toggles.depth_test;
  look.painter = toggles.painter;
  look.cull = toggles.cull;
  View view;
  Shading own = Shading::automatic;
  glm::vec3 background = kDefaultBackground;
  if (!demo_) {
    CameraSpec camera;
    camera.azimuth_degrees = orbit.azimuth_degrees;
    camera.elevation_degrees = orbit.elevation_degrees;
    camera.projection = toggles.orthographic ? Projection::orthographic : Projection::perspective;
    view = make_view(camera, framing_, aspect);
    view.view_from_world = translate(glm::vec3(orbit.pan * framing_.radius, 0.0f)) * view.view_from_world;
  } else {
    DemoFrame demo = demo_frame(*demo_, seconds, aspect);
    for (std::size_t i = 0; i < demo.instances.size(); ++i)
      scene_.set_transform(i, demo.instances[i].world_from_object);
    view = demo.view;
    // The demo turns about its instances' centre, as seen from the document's camera.
    glm::vec3 center(0.0f);
    for (const Instance& instance : demo.instances)
      center += glm::vec3(view.view_from_world * instance.world_from_object * glm::vec4(0, 0, 0, 1));
    center /= static_cast<float>(demo.instances.size());
    const glm::mat4 turn =
        rotate_x(glm::radians(orbit.elevation_degrees)) * rotate_y(glm::radians(orbit.azimuth_degrees));
    const float reach = std::max(std::abs(center.z), 1.0f) * 0.5f;
    view.view_from_world = translate(glm::vec3(orbit.pan * reach, 0.0f)) * translate(center) * turn *
                           translate(-center) * view.view_from_world;
    // Orthographic: the same size at the centre's depth, where the perspective shows it.
    const bool perspective = view.clip_from_view[2][3] == -1.0f;
    if (toggles.orthographic && perspective) {
      const float depth = std::max(std::abs(center.z), view.near);
      const float half_w = depth / view.clip_from_view[0][0], half_h = depth / view.clip_from_view[1][1];
      view.clip_from_view = ortho(-half_w, half_w, -half_h, half_h, view.near, view.far);
    }
    own = demo_->shading;
    background = demo_->background;
  }
  view.clip_from_view = scale(glm::vec3(orbit.zoom, orbit.zoom, 1.0f)) * view.clip_from_view;
  const glm::vec4 clear = clear_color(look, background);
  const std::span<const Light> lights = demo_ ? std::span<const Light>() : std::span<const Light>(mesh_->lights);
  SceneOptions options = scene_options(look, view.view_from_world, own, glm::vec3(clear), lights);
  if (!demo_) options.eye_dome_lighting = eye_dome_lighting_for(look, *mesh_);
  return Frame{&scene_, view, options, clear};
}

void draw_frame(Renderer& renderer, std::optional<Framebuffer>& target, int width, int height, Showing& showing,
                double seconds, const Toggles& toggles, const Orbit& orbit, const LookSpec& base) {
  const int samples = toggles.antialias ? 4 : 1;
  if (!target || target->width() != width || target->height() != height || target->samples() != samples)
    target.emplace(width, height, samples);
  const Showing::Frame frame =
      showing.frame(seconds, static_cast<float>(width) / static_cast<float>(height), toggles, orbit, base);
  renderer.clear(*target, frame.clear, 1.0f);
  frame.scene->render(renderer, *target, frame.view, frame.options);
  renderer.finish(*target);
}

}  // namespace facet::viewer
