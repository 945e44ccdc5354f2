// viewer_state.hpp - what `facet view` shows: the model or demo, the toggles the keys flip, and the orbit camera.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "facet/demo_scenes.hpp"
#include "facet/framebuffer.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/view_spec.hpp"

namespace facet::viewer {

// The switches of the source documents' demos, flipped by keys (keys.cpp says which).
struct Toggles {
  bool wireframe = false;
  bool edges = false;
  std::optional<CullMode> cull;  // unset: the model's own, as `facet render` starts (open meshes show both sides)
  bool depth_test = true;
  bool painter = false;
  int shuffles = 0;                // times the triangle order was shuffled (0: the file's order)
  std::optional<Shading> shading;  // unset: the model's own look
  ColorMap color_map = ColorMap::none;  // colours from where each vertex lies (LookSpec::color_map)
  bool orthographic = false;
  bool antialias = false;  // 4x multisampling
  bool paused = false;
  int steps = 0;  // frames (1/30 s each) to step the animation by, forward or back, before the next frame
  bool help = false;
};

// The orbit camera: turns and moves applied to the view `facet render` would start with.
struct Orbit {
  float azimuth_degrees = 0.0f;    // about the view's up axis, dragging left and right
  float elevation_degrees = 0.0f;  // dragging up and down, kept within +-89
  glm::vec2 pan{0.0f};             // in units of the model's framing radius, across the view
  float zoom = 1.0f;               // magnification of the view
};

// The mouse's gestures, in pixels, on a view `height` pixels high (the viewer and the browser page share them).
void turn_by(Orbit& orbit, glm::vec2 drag);             // left-drag: turn about the model
void pan_by(Orbit& orbit, glm::vec2 drag, int height);  // right- or shift-drag: move across the view
void zoom_by(Orbit& orbit, float wheel_steps);          // the wheel, one step a notch: 10% each

// What is shown: a model file or a demo, its meshes prepared in a Scene.
class Showing {
 public:
  // Loads a model (throws InputError as load_model does) or makes a demo. A model's first animation (a glTF
  // file's) plays, looping.
  static Showing model(const std::string& path, const LoadOptions& load = {});
  static Showing demo(Demo demo);

  const std::string& title() const { return title_; }
  // Whether the colour map can be drawn: intensity needs a model that has intensities.
  bool supports(ColorMap map) const {
    return map != ColorMap::intensity || (mesh_ && !mesh_->positions.empty() &&
                                          mesh_->intensities.size() == mesh_->positions.size());
  }
  bool animated() const { return demo_.has_value() || motion_ != nullptr; }

  // The frame at `seconds` of the animation for an aspect (width / height) with the toggles and orbit applied:
  // the scene to draw (its instances moved, its triangles shuffled as the toggles say), the view, the options and
  // the clear colour.
  struct Frame {
    Scene* scene;
    View view;
    SceneOptions options;
    glm::vec4 clear;
  };
  // `base` gives what the toggles leave alone (the environment and lights of the model's own look).
  Frame frame(double seconds, float aspect, const Toggles& toggles, const Orbit& orbit, const LookSpec& base = {});

 private:
  void rebuild_scene(int shuffles, ColorMap color_map);

  struct Motion;  // a model's animation: the model as read, a Poser, the clip's length

  std::string title_;
  std::optional<DemoModel> demo_;
  std::shared_ptr<Motion> motion_;
  double posed_at_ = 0.0;             // the moment mesh_ shows
  std::shared_ptr<const Mesh> mesh_;  // the model, or the demo's mesh, in the file's triangle order
  Framing framing_;
  Scene scene_;
  int scene_shuffles_ = -1;  // the shuffle the scene was built with
  ColorMap scene_color_map_ = ColorMap::none;  // and its colour map
};

// Draws what is shown at `seconds` of its animation into `target`, first (re)made at width x height with the
// samples the toggles ask for.
void draw_frame(Renderer& renderer, std::optional<Framebuffer>& target, int width, int height, Showing& showing,
                double seconds, const Toggles& toggles, const Orbit& orbit, const LookSpec& base = {});

// A copy of mesh with its triangles in a pseudo-random order fixed by `seed` (every per-triangle array moved
// with them), for showing what drawing order does without a depth test.
Mesh shuffled(const Mesh& mesh, int seed);

}  // namespace facet::viewer
